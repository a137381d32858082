#include "engine/assets/gltf_external_files.h"

#include <tiny_gltf.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"

namespace engine {
namespace {

bool exists(const std::string& file, void* self) {
    return static_cast<const GltfExternalFiles*>(self)->allows(file);
}

std::string expand(const std::string& file, void*) {
    return file;
}

bool read(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* self) {
    if (!static_cast<const GltfExternalFiles*>(self)->allows(file)) {
        if (err) *err += "not a file in the model's folder: " + file + "\n";
        return false;
    }
    try {
        *out = read_binary_file(file);
    } catch (const Error& e) {
        if (err) *err += std::string(e.what()) + "\n";
        return false;
    }
    return true;
}

bool write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "the loader writes no files\n";
    return false;
}

}  // namespace

bool GltfExternalFiles::allows(const std::string& file) const {
    if (folder_.empty()) return false;
    std::error_code ec;
    const auto absolute = std::filesystem::absolute(std::filesystem::path(file), ec).lexically_normal();
    if (ec) return false;
    const auto relative = absolute.lexically_relative(folder_);
    if (relative.empty() || *relative.begin() == "..") return false;
    return std::filesystem::is_regular_file(absolute, ec);
}

void GltfExternalFiles::install(tinygltf::TinyGLTF& loader) const {
    loader.SetFsCallbacks({&exists, &expand, &read, &write, const_cast<GltfExternalFiles*>(this)});
}

}  // namespace engine
