// The lossless WebP textures of a SOG scene through decode_webp (io/webp_texture.h), the decoder
// every SOG texture goes through. Contract: an RGBA8 texture of at least `min_pixels` texels, or
// engine::Error naming the file; the claimed size is checked against the file size before libwebp
// allocates. The first input byte picks min_pixels (0..255), the rest is the file.
#include "engine/core/error.h"
#include "splat_fuzz_support.h"
#include "splat_lod/core/webp_texture.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string name = "fuzz.webp";
    const std::uint64_t min_pixels = data[0];
    splat_lod::io::RgbaTexture texture;
    try {
        texture = splat_lod::io::decode_webp(splat_fuzz::bytes_of(data + 1, size - 1), name, min_pixels);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, name);
        return 0;
    }
    splat_fuzz::require(texture.width > 0 && texture.height > 0, "the texture has a size");
    splat_fuzz::require(texture.pixels() >= min_pixels, "the texture holds min_pixels texels");
    splat_fuzz::require(texture.rgba.size() == 4 * texture.pixels(), "rgba holds 4 bytes per texel");
    return 0;
}
