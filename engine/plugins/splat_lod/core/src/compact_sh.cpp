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

// The band's scale for exponent e: M·2^(−e/2).
float band_scale(float band_max, int e) {
    return band_max * std::exp2(-0.5f * float(e));
}

// q in [−levels, levels] for v against scale s; s = 0 gives 0.
int quantise_coefficient(float v, float s, int levels) {
    if (!(s > 0.0f)) return 0;
    return static_cast<int>(std::clamp(std::round(double(v) / s * levels), double(-levels), double(levels)));
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

// q of coefficient j (0-based over the band's channels) of `band`.
int read_q(std::span<const std::uint32_t> words, const CompactShBand& code, int j) {
    if (code.bits == 0) {  // trits: 0, 1, 2 for q = 0, 1, −1
        std::uint32_t t = 0;
        if (j < kTritsInWord) {
            t = words[3];
            for (int d = 0; d < j; ++d) t /= 3;
            t %= 3;
        } else {
            t = read_bits(words, kLastTritOffset, 2);
        }
        return t == 1 ? 1 : (t == 2 ? -1 : 0);  // a damaged last trit of 3 reads as 0
    }
    const std::uint32_t field = read_bits(words, code.offset + j * code.bits, code.bits);
    const std::uint32_t sign = 1u << (code.bits - 1);
    return static_cast<int>(field ^ sign) - static_cast<int>(sign);  // two's complement of `bits` bits
}

void write_q(std::span<std::uint32_t> words, const CompactShBand& code, int j, int q) {
    if (code.bits == 0) {
        const std::uint32_t t = q < 0 ? 2u : static_cast<std::uint32_t>(q);
        if (j >= kTritsInWord) return write_bits(words, kLastTritOffset, 2, t);
        std::uint32_t power = 1;
        for (int d = 0; d < j; ++d) power *= 3;
        words[3] += t * power;
        return;
    }
    write_bits(words, code.offset + j * code.bits, code.bits, static_cast<std::uint32_t>(q));
}

// The exponent of the least squared error of `values` at `levels` (the first, largest scale, on ties).
int best_exponent(std::span<const float> values, float band_max, int levels) {
    int best = 0;
    double best_error = INFINITY;
    for (int e = 0; e < kCompactShExponents; ++e) {
        const float s = band_scale(band_max, e);
        double error = 0.0;
        for (const float v : values) {
            const double d = double(v) - dequantise_coefficient(quantise_coefficient(v, s, levels), s, levels);
            error += d * d;
        }
        if (error < best_error) {
            best_error = error;
            best = e;
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
    for (int band = 1; band <= stored; ++band) {
        const CompactShBand code = compact_sh_band(sh_degree, band);
        const int n = 3 * band_coefficients(band);
        for (int j = 0; j < n; ++j)
            values[static_cast<std::size_t>(j)] = cloud.sh_rest_at(i, first_coefficient(band) + j / 3, j % 3);
        const float band_max = page.sh_max[band - 1];
        const int e = best_exponent(std::span(values).first(static_cast<std::size_t>(n)), band_max, code.levels);
        write_bits(sh_words, kExponentBits * (band - 1), kExponentBits, static_cast<std::uint32_t>(e));
        for (int j = 0; j < n; ++j)
            write_q(sh_words, code, j,
                    quantise_coefficient(values[static_cast<std::size_t>(j)], band_scale(band_max, e), code.levels));
    }
}

void decode_compact_sh(std::span<const std::uint32_t> sh_words, const CompactPage& page, int sh_degree,
                       std::span<float> rest) {
    for (int band = 1; band <= sh_degree; ++band) {
        const CompactShBand code = compact_sh_band(sh_degree, band);
        const auto e = static_cast<int>(read_bits(sh_words, kExponentBits * (band - 1), kExponentBits));
        const float s = band_scale(page.sh_max[band - 1], e);
        for (int j = 0; j < 3 * band_coefficients(band); ++j)
            rest[static_cast<std::size_t>(3 * (first_coefficient(band) - 1) + j)] =
                dequantise_coefficient(read_q(sh_words, code, j), s, code.levels);
    }
}

}  // namespace splat_lod
