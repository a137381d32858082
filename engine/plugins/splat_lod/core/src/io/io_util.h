#pragma once
// Helpers shared by the splat readers: error messages that name the file and byte offset,
// overflow-checked sizes, and bounds-checked little-endian reads.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "engine/core/error.h"

namespace splat_lod::io {

// Whether a path read from a file names something below the folder it is relative to: relative,
// without a root, with no ".." component (so a file can never make a reader open one elsewhere).
bool stays_below_folder(const std::filesystem::path& path);

// "<name>: <message>"
[[noreturn]] void fail_file(const std::string& name, std::string_view message);
// "<name>: offset <offset>: <message>"
[[noreturn]] void fail_at(const std::string& name, std::uint64_t offset, std::string_view message);

// a * b and a + b, or an error naming `what` when the result does not fit in 64 bits.
std::uint64_t checked_mul(std::uint64_t a, std::uint64_t b, const std::string& name, std::string_view what);
std::uint64_t checked_add(std::uint64_t a, std::uint64_t b, const std::string& name, std::string_view what);

// Little-endian loads from a position the caller has bounds-checked.
inline std::uint32_t load_u32le(const std::uint8_t* p) {
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}
inline std::uint64_t load_u64le(const std::uint8_t* p) {
    return static_cast<std::uint64_t>(load_u32le(p)) | static_cast<std::uint64_t>(load_u32le(p + 4)) << 32;
}
inline float load_f32le(const std::uint8_t* p) {
    const std::uint32_t bits = load_u32le(p);
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}
inline void store_u32le(std::uint8_t* p, std::uint32_t v) {
    p[0] = static_cast<std::uint8_t>(v);
    p[1] = static_cast<std::uint8_t>(v >> 8);
    p[2] = static_cast<std::uint8_t>(v >> 16);
    p[3] = static_cast<std::uint8_t>(v >> 24);
}
inline void store_f32le(std::uint8_t* p, float value) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    store_u32le(p, bits);
}

// The bytes [offset, offset + size) or an error saying the file ends too early for `what`.
std::span<const std::uint8_t> slice(std::span<const std::uint8_t> bytes, std::uint64_t offset, std::uint64_t size,
                                    const std::string& name, std::string_view what);

// Unit value (e.g. a byte / 255) to an opacity logit, clamped so the result stays finite.
float unit_to_logit(float opacity);

// Activations used by the writers and by format conversions.
float sigmoid(float x);

}  // namespace splat_lod::io
