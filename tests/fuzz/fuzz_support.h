#pragma once
// Shared by the fuzz harnesses of the engine and its plugins (tests/fuzz/README.md). A harness calls
// one reader on the input, treats engine::Error as the expected outcome of bad input and checks what
// a successful read returns against the reader's documented promises; a broken promise calls
// broken_promise(), which aborts, so libFuzzer records the input as a crash.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "engine/core/error.h"

namespace engine_fuzz {

// Prints "<harness>: broken promise: <what>" and aborts.
[[noreturn]] void broken_promise(const std::string& what);
inline void require(bool ok, const std::string& what) {
    if (!ok) broken_promise(what);
}

bool finite(const glm::vec2& v);
bool finite(const glm::vec3& v);
bool finite(const glm::vec4& v);
bool finite(const glm::mat4& m);
bool unit_length(const glm::vec3& v, float tolerance = 1e-3f);

inline std::span<const std::uint8_t> bytes_of(const std::uint8_t* data, std::size_t size) {
    return {data, size};
}
inline std::string text_of(const std::uint8_t* data, std::size_t size) {
    return std::string(reinterpret_cast<const char*>(data), size);
}

// Readers promise messages that start with the file's name ("<name>: ..."); a message without it
// breaks that promise. With FUZZ_SHOW_ERRORS set in the environment every message is printed.
void check_error_names(const std::exception& error, const std::string& name);

// A folder private to this process (under the system temporary folder), made on first use and
// removed at exit. Harnesses whose reader takes a path put their files here, and scene assets
// must stay inside it.
const std::filesystem::path& sandbox_dir();
// True when `path` lies inside sandbox_dir() after lexical normalisation.
bool inside_sandbox(const std::filesystem::path& path);
void write_file(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

// Files that inputs may refer to by name, written into sandbox_dir() once (the seeds use them):
//   buffer.bin     one triangle: 3 positions, 3 normals, 3 uvs (float), 3 u16 indices + 2 pad bytes
//   texture.png    2x2 RGBA
//   triangle.gltf  the triangle, with buffer.bin and texture.png as external files
// (a plugin's harnesses may add their own: splat_fuzz_support.h)
void write_sandbox_assets();

// Engine warnings (e.g. the glTF loader's) would flood the fuzzer's output: errors only.
void quiet_engine_log();

}  // namespace engine_fuzz
