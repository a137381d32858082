#include "io_util.h"

#include <algorithm>
#include <cmath>

#include "splat_lod/core/splat_io.h"

namespace splat_lod::io {

bool stays_below_folder(const std::filesystem::path& path) {
    if (path.is_absolute() || path.has_root_name() || path.has_root_directory()) return false;
    return std::none_of(path.begin(), path.end(), [](const std::filesystem::path& part) { return part == ".."; });
}

void fail_file(const std::string& name, std::string_view message) {
    engine::fail(name + ": " + std::string(message));
}

void fail_at(const std::string& name, std::uint64_t offset, std::string_view message) {
    engine::fail(name + ": offset " + std::to_string(offset) + ": " + std::string(message));
}

std::uint64_t checked_mul(std::uint64_t a, std::uint64_t b, const std::string& name, std::string_view what) {
    std::uint64_t result = 0;
    if (__builtin_mul_overflow(a, b, &result))
        fail_file(name, std::string(what) + ": size overflows 64 bits (" + std::to_string(a) + " x " +
                            std::to_string(b) + ")");
    return result;
}

std::uint64_t checked_add(std::uint64_t a, std::uint64_t b, const std::string& name, std::string_view what) {
    std::uint64_t result = 0;
    if (__builtin_add_overflow(a, b, &result)) fail_file(name, std::string(what) + ": size overflows 64 bits");
    return result;
}

std::span<const std::uint8_t> slice(std::span<const std::uint8_t> bytes, std::uint64_t offset, std::uint64_t size,
                                    const std::string& name, std::string_view what) {
    if (offset > bytes.size() || size > bytes.size() - offset)
        fail_at(name, offset,
                std::string(what) + " needs " + std::to_string(size) + " bytes but the data ends at " +
                    std::to_string(bytes.size()) + " (truncated?)");
    return bytes.subspan(static_cast<std::size_t>(offset), static_cast<std::size_t>(size));
}

float unit_to_logit(float opacity) {
    const float a = std::clamp(opacity, kOpacityClamp, 1.0f - kOpacityClamp);
    return std::log(a / (1.0f - a));
}

float sigmoid(float x) {
    return 1.0f / (1.0f + std::exp(-x));
}

}  // namespace splat_lod::io

namespace splat_lod {

float opacity_to_logit(float opacity) {
    return io::unit_to_logit(opacity);
}

}  // namespace splat_lod
