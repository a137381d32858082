#pragma once
// Shared by the fuzz harnesses (tests/fuzz/README.md). A harness calls one reader on the input,
// treats engine::Error as the expected outcome of bad input and checks what a successful read
// returns against the reader's documented promises; a broken promise calls broken_promise(),
// which aborts, so libFuzzer records the input as a crash.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "engine/core/error.h"
#include "splat_lod/core/splat_cloud.h"

namespace splat_fuzz {

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

// What splat_io.h promises of every cloud a reader returns: consistent arrays, no NaN/Inf in any
// attribute, unit quaternions, and a report whose counts add up.
void check_cloud(const splat_lod::SplatCloud& cloud, const splat_lod::LoadReport& report);

// One splat reader's byte-span overload on the input (read(bytes, name, &report)): an engine::Error
// must name the file, a returned cloud must keep check_cloud's promises.
template <class Read>
int fuzz_splat_reader(const std::uint8_t* data, std::size_t size, const std::string& name, Read read) {
    splat_lod::LoadReport report;
    splat_lod::SplatCloud cloud;
    try {
        cloud = read(bytes_of(data, size), name, &report);
    } catch (const engine::Error& e) {  // anything else escapes: a finding
        check_error_names(e, name);
        return 0;
    }
    check_cloud(cloud, report);
    return 0;
}

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
//   cloud.ply      a 3-Gaussian INRIA PLY (SH degree 1);  cloud.splat  the same as .splat
void write_sandbox_assets();

// Engine warnings (e.g. the glTF loader's) would flood the fuzzer's output: errors only.
void quiet_engine_log();

}  // namespace splat_fuzz
