#include "splat_lod/core/webp_texture.h"

#include <memory>

#include <webp/decode.h>

#include "engine/core/file_io.h"
#include "io_util.h"

namespace splat_lod::io {
namespace {

// Lossless WebP of real SOG textures stores about one byte per texel; even a flat image needs a
// few bytes per 128×128 block. Claiming more texels than this per byte of file is a lie.
constexpr std::uint64_t kMaxPixelsPerByte = 16384;
constexpr std::uint64_t kAlwaysAllowedPixels = 1 << 16;

struct WebpDeleter {
    void operator()(std::uint8_t* p) const { WebPFree(p); }
};

}  // namespace

RgbaTexture load_webp(const std::filesystem::path& file, std::uint64_t min_pixels) {
    return decode_webp(engine::read_binary_file(file), file.string(), min_pixels);
}

RgbaTexture decode_webp(std::span<const std::uint8_t> bytes, const std::string& name, std::uint64_t min_pixels) {
    RgbaTexture texture;
    texture.name = name;
    int width = 0;
    int height = 0;
    if (!WebPGetInfo(bytes.data(), bytes.size(), &width, &height)) fail_file(texture.name, "not a WebP image");
    const std::uint64_t pixels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    if (pixels > kAlwaysAllowedPixels + kMaxPixelsPerByte * bytes.size())
        fail_file(texture.name, "claims " + std::to_string(width) + "x" + std::to_string(height) +
                                    " texels, implausible for a " + std::to_string(bytes.size()) + "-byte file");
    if (pixels < min_pixels)
        fail_file(texture.name, std::to_string(width) + "x" + std::to_string(height) + " texels, but " +
                                    std::to_string(min_pixels) + " are needed");
    std::unique_ptr<std::uint8_t, WebpDeleter> decoded(WebPDecodeRGBA(bytes.data(), bytes.size(), &width, &height));
    if (!decoded) fail_file(texture.name, "WebP decoding failed (corrupt or truncated)");
    texture.width = width;
    texture.height = height;
    texture.rgba.assign(decoded.get(), decoded.get() + 4 * texture.pixels());
    return texture;
}

}  // namespace splat_lod::io
