#pragma once
// The files a glTF model may read besides itself (buffers, images): regular files in its folder or
// below it, read through tinygltf's file-system callbacks. tinygltf would otherwise also try the
// working directory and follow ".." and absolute URIs anywhere, devices and FIFOs included. Used by
// the mesh loader and by plugins that read glTF themselves.
#include <filesystem>
#include <string>

namespace tinygltf {
class TinyGLTF;
}

namespace engine {

class GltfExternalFiles {
public:
    // `folder` absolute and normalised; empty: no external file at all (a model read from memory).
    explicit GltfExternalFiles(std::filesystem::path folder) : folder_(std::move(folder)) {}
    bool allows(const std::string& file) const;
    // Makes `loader` read external files through this object, which must outlive its loads; writing
    // is refused.
    void install(tinygltf::TinyGLTF& loader) const;
    const std::filesystem::path& folder() const { return folder_; }

private:
    std::filesystem::path folder_;
};

}  // namespace engine
