#pragma once
// The compact resident format of the GPU scene (docs/gpu_storage.md): each Gaussian in 20 bytes plus
// its higher SH bands in 8 or 16 bytes, quantised against ranges fitted to its page (the 256
// Gaussians one project workgroup reads). The GPU scene encodes with these functions, the project pass
// decodes the same bits (common_splat_storage.glsl), and compact_round_trip() gives the CPU reference
// exactly what the GPU draws, as a cloud.
//
// The 160-bit record, five little-endian 32-bit words (bit offsets within each word):
//   word 0  position x (0–15), position y (16–31)         16 bits each, over the page's box
//   word 1  position z (0–15), opacity (16–23), log-scale 0 (24–31)
//   word 2  rotation: index of the largest |component| of (w, x, y, z) (30–31) and the other three in
//           order, 10 bits each (0–9, 10–19, 20–29), over [−1/√2, 1/√2]
//   word 3  log-scale 1 (0–7), log-scale 2 (8–15), colour red (16–23), green (24–31)
//   word 4  colour blue (0–7), level − 1 (8–9), coverage_min (10–20), coverage_max (21–31)
// Positions: lo + q·step per axis over the box of the page's drawable means (65535 steps). Opacity: the
// activated opacity q/255. Log-scales: lo + q·step over the page's range of all three (255 steps).
// Colour: the DC term as colour, kShC0·dc + 0.5, lo + q·step per channel over the page's range.
// Coverage bounds: code 0 is unset (−1), 1 is 0, 2..2047 are 2^(lo + (q − 2)·step) over the page's
// range of log2 of the positive bounds.
//
// The higher SH bands (1..degree) take 2, 4 and 4 words at degrees 1, 2 and 3, read as one bit string
// (bit b is bit b mod 32 of word b / 32). Each band b has a 4-bit exponent e_b at bits 4·(b − 1), and its
// coefficients, in SplatCloud::sh_rest order (coefficient-major, channel-minor), are q·s/L with
// s = M_b·2^(−e_b/2), M_b the page's largest |coefficient| of the band, and q a signed integer in [−L, L]:
//   degree 1  band 1: 6-bit fields (L = 31) from bit 4
//   degree 2  band 1: 6-bit fields (L = 31) from bit 8; band 2: 4-bit fields (L = 7) from bit 62
//   degree 3  band 1: 4-bit fields (L = 7) from bit 12; band 2: 3-bit fields (L = 3) from bit 48;
//             band 3: trits (L = 1), the first 20 as the base-3 digits of word 3 (digit j the j-th
//             coefficient), the 21st in bits 93–94
// A field holds q in two's complement, a trit 0, 1 or 2 for q = 0, 1 or −1, so that zero words decode to
// zero. The encoder picks each band's exponent by the least squared error of its coefficients, among
// the smallest scale at or above their largest magnitude and the next two (four for trits).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "splat_lod/core/splat_cloud.h"

namespace splat_lod {

inline constexpr std::size_t kCompactWords = 5;       // 32-bit words of one record (20 bytes)
inline constexpr std::size_t kCompactPageSize = 256;  // Gaussians one page's ranges cover
inline constexpr std::uint32_t kCompactCoverageCodes = 2047;

// 32-bit words of SH bands 1..degree per Gaussian: 0, 2, 4 and 4 for degree 0..3.
constexpr std::uint32_t compact_sh_words(int sh_degree) {
    return sh_degree <= 0 ? 0u : (sh_degree == 1 ? 2u : 4u);
}

// How band `band` (1..degree) of a Gaussian stored with SH degree `sh_degree` is coded: q in [−levels,
// levels] per coefficient, `bits`-bit fields from bit `offset` (bits 0: trits, see above).
struct CompactShBand {
    int levels = 0, offset = 0, bits = 0;
};
CompactShBand compact_sh_band(int sh_degree, int band);
inline constexpr int kCompactShExponents = 16;  // e_b in 0..15: scales M_b down to M_b·2^−7.5

// The ranges one page's records are quantised against (GpuPageCodec on the GPU).
struct CompactPage {
    glm::vec3 position_lo{0.0f}, position_step{0.0f};
    float log_scale_lo = 0.0f, log_scale_step = 0.0f;
    glm::vec3 colour_lo{0.0f}, colour_step{0.0f};
    float coverage_lo = 0.0f, coverage_step = 0.0f;  // log2 of the bounds
    glm::vec3 sh_max{0.0f};                          // bands 1, 2, 3: the largest |coefficient|
};

using CompactRecord = std::array<std::uint32_t, kCompactWords>;

// One record decoded: what the project pass reads (the rotation unit length, the opacity activated).
struct CompactGaussian {
    glm::vec3 position{0.0f};
    Rotation rotation;
    glm::vec3 log_scale{0.0f};
    float opacity = 0.0f;
    glm::vec3 sh_dc{0.0f};
    std::uint8_t level = 1;
    float coverage_min = -1.0f, coverage_max = -1.0f;
};

// Whether the GPU draws Gaussian i at all: finite attributes (SH up to the cloud's degree included)
// and a non-zero rotation. Others are stored with opacity 0 and left out of every range.
bool gaussian_is_drawable(const SplatCloud& cloud, std::size_t i);

// The ranges of Gaussians [first, first + count) of `cloud` with SH bands up to `sh_degree`.
CompactPage fit_compact_page(const SplatCloud& cloud, std::size_t first, std::size_t count, int sh_degree);

// Gaussian i against its page's ranges; `sh_words` receives compact_sh_words(sh_degree) words.
CompactRecord encode_compact(const SplatCloud& cloud, std::size_t i, const CompactPage& page);
void encode_compact_sh(const SplatCloud& cloud, std::size_t i, const CompactPage& page, int sh_degree,
                       std::span<std::uint32_t> sh_words);

CompactGaussian decode_compact(const CompactRecord& record, const CompactPage& page);
// Coefficients 1..(d + 1)² − 1 of the three channels, as SplatCloud::sh_rest orders them.
void decode_compact_sh(std::span<const std::uint32_t> sh_words, const CompactPage& page, int sh_degree,
                       std::span<float> rest);

// Decodes a record and its SH words into Gaussian i of `out` (sized, with SH degree `sh_degree`): the
// opacity as a logit (−100 for an opacity of 0, below every threshold), level and coverage bounds set.
void decode_compact_into(const CompactRecord& record, std::span<const std::uint32_t> sh_words, const CompactPage& page,
                         int sh_degree, SplatCloud& out, std::size_t i);

// The cloud the GPU scene draws when it stores `cloud` compact with SH up to `sh_degree`: every
// Gaussian encoded in pages of kCompactPageSize from index 0 and decoded again (drawable ones; the
// others get an opacity logit of −100, below every threshold).
SplatCloud compact_round_trip(const SplatCloud& cloud, int sh_degree);

}  // namespace splat_lod
