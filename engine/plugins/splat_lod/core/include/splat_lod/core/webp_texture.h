#pragma once
// Lossless WebP textures of a SOG scene, decoded to RGBA8 with libwebp.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace splat_lod::io {

struct RgbaTexture {
    std::vector<std::uint8_t> rgba;  // width * height * 4, rows top to bottom
    int width = 0;
    int height = 0;
    std::string name;  // the file, for messages

    std::uint64_t pixels() const { return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height); }
    const std::uint8_t* texel(std::uint64_t index) const { return rgba.data() + 4 * index; }
};

// Decodes `file`, which must hold at least `min_pixels` texels. The dimensions are checked against
// the file size before decoding, so a tiny file cannot make libwebp allocate gigabytes.
RgbaTexture load_webp(const std::filesystem::path& file, std::uint64_t min_pixels);
// The same from the file's bytes; `name` is the file named in error messages.
RgbaTexture decode_webp(std::span<const std::uint8_t> bytes, const std::string& name, std::uint64_t min_pixels);

}  // namespace splat_lod::io
