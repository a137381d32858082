#include "fuzz_support.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

#include <unistd.h>

#include "engine/core/log.h"

namespace engine_fuzz {
namespace {

std::filesystem::path make_sandbox() {
    const auto dir = std::filesystem::temp_directory_path() / ("engine_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
}

void remove_sandbox() {
    std::error_code ec;
    std::filesystem::remove_all(sandbox_dir(), ec);
}

bool finite(float v) {
    return std::isfinite(v);
}

constexpr std::uint8_t kTexturePng[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00, 0x00,
    0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x06, 0x00, 0x00, 0x00, 0x72, 0xb6, 0x0d, 0x24, 0x00, 0x00, 0x00, 0x13, 0x49,
    0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0xf8, 0xcf, 0xc0, 0xf0, 0x1f, 0x0c, 0x81, 0x34, 0x08, 0x34, 0x00, 0x00, 0x49,
    0x49, 0x09, 0x78, 0x9c, 0x51, 0x17, 0x92, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

constexpr const char* kTriangleGltf = R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
 "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                             "indices": 3, "material": 0}]}],
 "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
 "textures": [{"source": 0}], "images": [{"uri": "texture.png"}],
 "buffers": [{"uri": "buffer.bin", "byteLength": 104}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96},
                 {"buffer": 0, "byteOffset": 96, "byteLength": 6}],
 "accessors": [{"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                "min": [0, 0, 0], "max": [1, 1, 0]},
               {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"},
               {"bufferView": 0, "byteOffset": 72, "componentType": 5126, "count": 3, "type": "VEC2"},
               {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]}
)";

std::vector<std::uint8_t> triangle_buffer() {
    const float values[] = {0, 0, 0, 1, 0, 0, 0, 1, 0,  // positions
                            0, 0, 1, 0, 0, 1, 0, 0, 1,  // normals
                            0, 0, 1, 0, 0, 1};          // uvs
    const std::uint16_t indices[] = {0, 1, 2, 0};       // the last one is padding
    std::vector<std::uint8_t> bytes(sizeof values + sizeof indices);
    std::memcpy(bytes.data(), values, sizeof values);
    std::memcpy(bytes.data() + sizeof values, indices, sizeof indices);
    return bytes;
}

}  // namespace

void broken_promise(const std::string& what) {
    std::fprintf(stderr, "fuzz harness: broken promise: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

void check_error_names(const std::exception& error, const std::string& name) {
    const std::string message = error.what();
    // FUZZ_SHOW_ERRORS=1 prints every error, e.g. to see why a seed is rejected.
    static const bool show = std::getenv("FUZZ_SHOW_ERRORS") != nullptr;
    if (show) std::fprintf(stderr, "fuzz harness: engine::Error: %s\n", message.c_str());
    require(message.rfind(name + ": ", 0) == 0, "the error message starts with \"" + name + ": \": " + message);
}

bool finite(const glm::vec2& v) {
    return finite(v.x) && finite(v.y);
}
bool finite(const glm::vec3& v) {
    return finite(v.x) && finite(v.y) && finite(v.z);
}
bool finite(const glm::vec4& v) {
    return finite(v.x) && finite(v.y) && finite(v.z) && finite(v.w);
}
bool finite(const glm::mat4& m) {
    return finite(m[0]) && finite(m[1]) && finite(m[2]) && finite(m[3]);
}

bool unit_length(const glm::vec3& v, float tolerance) {
    return std::fabs(glm::length(v) - 1.0f) <= tolerance;
}

const std::filesystem::path& sandbox_dir() {
    static const std::filesystem::path dir = [] {
        auto made = make_sandbox();
        std::atexit(remove_sandbox);
        return made;
    }();
    return dir;
}

bool inside_sandbox(const std::filesystem::path& path) {
    std::error_code ec;
    const auto absolute = std::filesystem::absolute(path, ec).lexically_normal();
    if (ec) return false;
    const auto relative = absolute.lexically_relative(sandbox_dir());
    return !relative.empty() && *relative.begin() != "..";
}

void write_file(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) broken_promise("cannot write the harness's own file " + path.string());
}

void write_sandbox_assets() {
    static const bool written = [] {
        const auto& dir = sandbox_dir();
        write_file(dir / "buffer.bin", triangle_buffer());
        write_file(dir / "texture.png", kTexturePng);
        const std::string gltf = kTriangleGltf;
        write_file(dir / "triangle.gltf", std::span(reinterpret_cast<const std::uint8_t*>(gltf.data()), gltf.size()));
        return true;
    }();
    (void)written;
}

void quiet_engine_log() {
    engine::set_log_level(engine::LogLevel::error);
}

}  // namespace engine_fuzz
