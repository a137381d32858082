// The higher SH bands of the compact resident format (compact_gaussians.h states the bits).
#include <algorithm>
#include <array>
#include <cmath>

#include "splat_lod/core/compact_gaussians.h"

namespace splat_lod {
namespace {

constexpr int kExponentBits = 4;
constexpr int kTritsInWord = 20;     // 3^20 < 2^32
constexpr int kLastTritOffset = 93;  // degree 3: the 21st trit of band 3

// The first coefficient (1..15) of band b and the band's coefficient count per channel.
constexpr int first_coefficient(int band) {
    return band * band;
}
constexpr int band_coefficients(int band) {
    return 2 * band + 1;
}

// 2^(−e/2) for e = 0..15, as common_splat_storage.glsl has them (the same literals).
constexpr std::array<float, kCompactShExponents> kHalfOctaves = {
    1.0f,      0.70710678118654752f,  0.5f,       0.35355339059327376f,  0.25f,    0.17677669529663688f,
    0.125f,    0.08838834764831844f,  0.0625f,    0.04419417382415922f,  0.03125f, 0.02209708691207961f,
    0.015625f, 0.011048543456039805f, 0.0078125f, 0.0055242717280199025f};

// The band's scale for exponent e: M·2^(−e/2).
float band_scale(float band_max, int e) {
    return band_max * kHalfOctaves[static_cast<std::size_t>(e)];
}

// q in [−levels, levels] for v against scale s; s = 0 gives 0.
int quantise_coefficient(float v, float s, int levels) {
    if (!(s > 0.0f)) return 0;
    return static_cast<int>(std::clamp(std::nearbyint(v / s * float(levels)), float(-levels), float(levels)));
}

float dequantise_coefficient(int q, float s, int levels) {
    return s * (float(q) / float(levels));
}

std::uint32_t read_bits(std::span<const std::uint32_t> words, int offset, int bits) {
    const int word = offset / 32, shift = offset % 32;
    std::uint64_t v = words[static_cast<std::size_t>(word)] >> shift;
    if (shift + bits > 32) v |= std::uint64_t{words[static_cast<std::size_t>(word) + 1]} << (32 - shift);
    return static_cast<std::uint32_t>(v & ((std::uint64_t{1} << bits) - 1));
}

void write_bits(std::span<std::uint32_t> words, int offset, int bits, std::uint32_t value) {
    const std::uint64_t v = std::uint64_t{value & ((1u << bits) - 1u)} << (offset % 32);
    words[static_cast<std::size_t>(offset / 32)] |= static_cast<std::uint32_t>(v);
    if (offset % 32 + bits > 32)
        words[static_cast<std::size_t>(offset / 32) + 1] |= static_cast<std::uint32_t>(v >> 32);
}

// The q of a band's n coefficients (0-based over its channels) into `q`.
void read_band(std::span<const std::uint32_t> words, const CompactShBand& code, int n, std::span<int> q) {
    if (code.bits == 0) {  // trits 0, 1, 2 for q = 0, 1, −1; a damaged last trit of 3 reads as 0
        const auto trit = [](std::uint32_t t) { return t == 1 ? 1 : (t == 2 ? -1 : 0); };
        std::uint32_t digits = words[3];
        for (int j = 0; j < std::min(n, kTritsInWord); ++j, digits /= 3)
            q[static_cast<std::size_t>(j)] = trit(digits % 3);
        if (n > kTritsInWord) q[kTritsInWord] = trit(read_bits(words, kLastTritOffset, 2));
        return;
    }
    const std::uint32_t sign = 1u << (code.bits - 1);
    for (int j = 0; j < n; ++j) {
        const std::uint32_t field = read_bits(words, code.offset + j * code.bits, code.bits);
        q[static_cast<std::size_t>(j)] = static_cast<int>(field ^ sign) - static_cast<int>(sign);  // two's complement
    }
}

void write_band(std::span<std::uint32_t> words, const CompactShBand& code, std::span<const int> q) {
    const int n = static_cast<int>(q.size());
    if (code.bits == 0) {
        const auto trit = [](int v) { return v < 0 ? 2u : static_cast<std::uint32_t>(v); };
        std::uint32_t digits = 0;
        for (int j = std::min(n, kTritsInWord) - 1; j >= 0; --j)
            digits = digits * 3 + trit(q[static_cast<std::size_t>(j)]);
        words[3] |= digits;
        if (n > kTritsInWord) write_bits(words, kLastTritOffset, 2, trit(q[kTritsInWord]));
        return;
    }
    for (int j = 0; j < n; ++j)
        write_bits(words, code.offset + j * code.bits, code.bits,
                   static_cast<std::uint32_t>(q[static_cast<std::size_t>(j)]));
}

// The exponent of the least squared error of `values` at `levels` (the largest scale on ties), with
// its q in `best_q`, among the exponents from the smallest scale that covers the values (never worse
// than the closed-form bound) to one octave of clipping, two for trits, where clipping pays most.
int best_exponent(std::span<const float> values, float band_max, int levels, std::span<int> best_q) {
    float m = 0.0f;
    for (const float v : values) m = std::max(m, std::abs(v));
    int first = 0;
    while (first + 1 < kCompactShExponents && band_scale(band_max, first + 1) >= m) ++first;
    const int last = std::min(first + (levels == 1 ? 4 : 2), kCompactShExponents - 1);
    int best = first;
    float best_error = INFINITY;
    std::array<int, 3 * 7> q{};
    for (int e = first; e <= last; ++e) {
        const float s = band_scale(band_max, e);
        float error = 0.0f;
        for (std::size_t j = 0; j < values.size(); ++j) {
            q[j] = quantise_coefficient(values[j], s, levels);
            const float d = values[j] - dequantise_coefficient(q[j], s, levels);
            error += d * d;
        }
        if (error < best_error) {
            best_error = error;
            best = e;
            std::copy_n(q.begin(), values.size(), best_q.begin());
        }
    }
    return best;
}

}  // namespace

CompactShBand compact_sh_band(int sh_degree, int band) {
    const int exponents = kExponentBits * sh_degree;
    if (sh_degree == 1) return {31, exponents, 6};
    if (sh_degree == 2) return band == 1 ? CompactShBand{31, exponents, 6} : CompactShBand{7, exponents + 9 * 6, 4};
    if (band == 1) return {7, exponents, 4};
    if (band == 2) return {3, exponents + 9 * 4, 3};
    return {1, 0, 0};
}

void encode_compact_sh(const SplatCloud& cloud, std::size_t i, const CompactPage& page, int sh_degree,
                       std::span<std::uint32_t> sh_words) {
    std::fill(sh_words.begin(), sh_words.end(), 0u);
    if (!gaussian_is_drawable(cloud, i)) return;
    const int stored = std::min(sh_degree, cloud.sh_degree);
    std::array<float, 3 * 7> values{};
    std::array<int, 3 * 7> q{};
    for (int band = 1; band <= stored; ++band) {
        const CompactShBand code = compact_sh_band(sh_degree, band);
        const auto n = static_cast<std::size_t>(3 * band_coefficients(band));
        for (std::size_t j = 0; j < n; ++j)
            values[j] = cloud.sh_rest_at(i, first_coefficient(band) + int(j / 3), int(j % 3));
        const int e = best_exponent(std::span(values).first(n), page.sh_max[band - 1], code.levels, q);
        write_bits(sh_words, kExponentBits * (band - 1), kExponentBits, static_cast<std::uint32_t>(e));
        write_band(sh_words, code, std::span(q).first(n));
    }
}

void decode_compact_sh(std::span<const std::uint32_t> sh_words, const CompactPage& page, int sh_degree,
                       std::span<float> rest) {
    std::array<int, 3 * 7> q{};
    for (int band = 1; band <= sh_degree; ++band) {
        const CompactShBand code = compact_sh_band(sh_degree, band);
        const int n = 3 * band_coefficients(band);
        const auto e = static_cast<int>(read_bits(sh_words, kExponentBits * (band - 1), kExponentBits));
        const float s = band_scale(page.sh_max[band - 1], e);
        read_band(sh_words, code, n, q);
        for (int j = 0; j < n; ++j)
            rest[static_cast<std::size_t>(3 * (first_coefficient(band) - 1) + j)] =
                dequantise_coefficient(q[static_cast<std::size_t>(j)], s, code.levels);
    }
}

}  // namespace splat_lod
