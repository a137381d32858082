// The compact resident format (compact_gaussians.h): page ranges, encoding and decoding.
#include "splat_lod/core/compact_gaussians.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

#include "splat_lod/core/gaussian_extent.h"

namespace splat_lod {
namespace {

constexpr float kHalfSqrt2 = 0.70710678118654752f;

// Quantises v to 0..codes against lo + q·step (0 when the range is a point).
std::uint32_t quantise(float v, float lo, float step, std::uint32_t codes) {
    if (!(step > 0.0f)) return 0;
    const double q = std::round((double(v) - lo) / step);
    return static_cast<std::uint32_t>(std::clamp(q, 0.0, double(codes)));
}

float dequantise(std::uint32_t q, float lo, float step) {
    return lo + float(q) * step;
}

// lo and step of [lo, hi] in `codes` steps; a range that is empty, a point or not finite gets step 0
// (everything decodes to lo).
void fit_range(double lo, double hi, std::uint32_t codes, float& out_lo, float& out_step) {
    if (!(lo <= hi)) lo = hi = 0.0;
    out_lo = static_cast<float>(lo);
    const double step = (hi - double(out_lo)) / codes * (1.0 + 1e-7);
    // Beyond the float range (a box from −3·10³⁸ to 3·10³⁸) the step saturates.
    const double largest = std::numeric_limits<float>::max();
    out_step = std::isfinite(step) && step > 0.0 ? static_cast<float>(std::min(step, largest)) : 0.0f;
}

std::uint32_t bits(std::uint32_t word, int offset, int count) {
    return (word >> offset) & ((1u << count) - 1u);
}

// The smallest-three code: the index of the largest |component| and the other three at 10 bits.
std::uint32_t encode_rotation(const Rotation& r) {
    const double n = std::sqrt(double(r.w) * r.w + double(r.x) * r.x + double(r.y) * r.y + double(r.z) * r.z);
    std::array<double, 4> q = {r.w / n, r.x / n, r.y / n, r.z / n};
    int largest = 0;
    for (int k = 1; k < 4; ++k)
        if (std::abs(q[k]) > std::abs(q[largest])) largest = k;
    const double sign = q[largest] < 0.0 ? -1.0 : 1.0;  // q and −q are the same rotation
    std::uint32_t code = std::uint32_t(largest) << 30;
    for (int k = 0, slot = 0; k < 4; ++k) {
        if (k == largest) continue;
        const double v = std::clamp(sign * q[k] / kHalfSqrt2, -1.0, 1.0);
        code |= static_cast<std::uint32_t>(std::lround((v * 0.5 + 0.5) * 1023.0)) << (10 * slot++);
    }
    return code;
}

Rotation decode_rotation(std::uint32_t code) {
    std::array<float, 4> q{};
    const int largest = static_cast<int>(code >> 30);
    float sum = 0.0f;
    for (int k = 0, slot = 0; k < 4; ++k) {
        if (k == largest) continue;
        q[k] = (float(bits(code, 10 * slot++, 10)) * (2.0f / 1023.0f) - 1.0f) * kHalfSqrt2;
        sum += q[k] * q[k];
    }
    q[largest] = std::sqrt(std::max(0.0f, 1.0f - sum));
    return Rotation{q[0], q[1], q[2], q[3]};
}

std::uint32_t encode_coverage(float v, const CompactPage& page) {
    if (std::isnan(v) || v < 0.0f) return 0;  // unset
    if (v == 0.0f) return 1;
    return 2 + quantise(std::log2(v), page.coverage_lo, page.coverage_step, kCompactCoverageCodes - 2);
}

float decode_coverage(std::uint32_t code, const CompactPage& page) {
    if (code == 0) return -1.0f;
    if (code == 1) return 0.0f;
    return std::exp2(dequantise(code - 2, page.coverage_lo, page.coverage_step));
}

float activated_opacity(const SplatCloud& cloud, std::size_t i) {
    return static_cast<float>(world::opacity_from_logit(cloud.opacity_logits[i]));
}

// The band (1..3) of SH coefficient k (1..15).
int band_of(int k) {
    return k < 4 ? 1 : (k < 9 ? 2 : 3);
}

}  // namespace

bool gaussian_is_drawable(const SplatCloud& cloud, std::size_t i) {
    const Rotation& q = cloud.rotations[i];
    const double norm = std::sqrt(double(q.w) * q.w + double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z);
    bool finite = std::isfinite(norm) && norm > 1e-12 && std::isfinite(cloud.opacity_logits[i]);
    for (int c = 0; c < 3; ++c)
        finite = finite && std::isfinite(cloud.positions[i][c]) && std::isfinite(cloud.log_scales[i][c]) &&
                 std::isfinite(cloud.sh_dc[i][c]);
    const std::size_t stride = cloud.sh_rest_stride();
    for (std::size_t k = 0; k < stride && finite; ++k) finite = std::isfinite(cloud.sh_rest[i * stride + k]);
    return finite;
}

CompactPage fit_compact_page(const SplatCloud& cloud, std::size_t first, std::size_t count, int sh_degree) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    glm::dvec3 p_lo(inf), p_hi(-inf), c_lo(inf), c_hi(-inf);
    double s_lo = inf, s_hi = -inf, cov_lo = inf, cov_hi = -inf;
    glm::dvec3 sh_max(0.0);
    const int rest = sh_rest_coeffs(std::min(sh_degree, cloud.sh_degree));
    for (std::size_t i = first; i < std::min(first + count, cloud.size()); ++i) {
        if (!gaussian_is_drawable(cloud, i)) continue;
        p_lo = glm::min(p_lo, glm::dvec3(cloud.positions[i]));
        p_hi = glm::max(p_hi, glm::dvec3(cloud.positions[i]));
        const glm::dvec3 colour = double(kShC0) * glm::dvec3(cloud.sh_dc[i]) + 0.5;
        c_lo = glm::min(c_lo, colour);
        c_hi = glm::max(c_hi, colour);
        for (int a = 0; a < 3; ++a) {
            s_lo = std::min(s_lo, double(cloud.log_scales[i][a]));
            s_hi = std::max(s_hi, double(cloud.log_scales[i][a]));
        }
        for (const auto* bounds : {&cloud.coverage_min, &cloud.coverage_max})
            if (!bounds->empty() && (*bounds)[i] > 0.0f && std::isfinite((*bounds)[i])) {
                cov_lo = std::min(cov_lo, std::log2(double((*bounds)[i])));
                cov_hi = std::max(cov_hi, std::log2(double((*bounds)[i])));
            }
        for (int k = 1; k <= rest; ++k)
            for (int c = 0; c < 3; ++c)
                sh_max[band_of(k) - 1] = std::max(sh_max[band_of(k) - 1], double(std::abs(cloud.sh_rest_at(i, k, c))));
    }
    CompactPage page;
    for (int a = 0; a < 3; ++a) {
        fit_range(p_lo[a], p_hi[a], 65535, page.position_lo[a], page.position_step[a]);
        fit_range(c_lo[a], c_hi[a], 255, page.colour_lo[a], page.colour_step[a]);
        page.sh_max[a] = static_cast<float>(sh_max[a]);
    }
    fit_range(s_lo, s_hi, 255, page.log_scale_lo, page.log_scale_step);
    fit_range(cov_lo, cov_hi, kCompactCoverageCodes - 2, page.coverage_lo, page.coverage_step);
    return page;
}

CompactRecord encode_compact(const SplatCloud& cloud, std::size_t i, const CompactPage& page) {
    CompactRecord r{};
    if (!gaussian_is_drawable(cloud, i)) return r;  // opacity 0: never drawn
    std::array<std::uint32_t, 3> p{}, s{}, c{};
    const glm::vec3 colour = kShC0 * cloud.sh_dc[i] + 0.5f;
    for (int a = 0; a < 3; ++a) {
        p[a] = quantise(cloud.positions[i][a], page.position_lo[a], page.position_step[a], 65535);
        s[a] = quantise(cloud.log_scales[i][a], page.log_scale_lo, page.log_scale_step, 255);
        c[a] = quantise(colour[a], page.colour_lo[a], page.colour_step[a], 255);
    }
    const auto opacity =
        static_cast<std::uint32_t>(std::lround(std::clamp(activated_opacity(cloud, i), 0.0f, 1.0f) * 255.0f));
    const std::uint32_t level = cloud.lod_level.empty() ? 0u : std::clamp<std::uint32_t>(cloud.lod_level[i], 1, 4) - 1;
    const float cmin = cloud.coverage_min.empty() ? -1.0f : cloud.coverage_min[i];
    const float cmax = cloud.coverage_max.empty() ? -1.0f : cloud.coverage_max[i];
    r[0] = p[0] | p[1] << 16;
    r[1] = p[2] | opacity << 16 | s[0] << 24;
    r[2] = encode_rotation(cloud.rotations[i]);
    r[3] = s[1] | s[2] << 8 | c[0] << 16 | c[1] << 24;
    r[4] = c[2] | level << 8 | encode_coverage(cmin, page) << 10 | encode_coverage(cmax, page) << 21;
    return r;
}

CompactGaussian decode_compact(const CompactRecord& r, const CompactPage& page) {
    CompactGaussian g;
    const std::array<std::uint32_t, 3> p = {bits(r[0], 0, 16), bits(r[0], 16, 16), bits(r[1], 0, 16)};
    const std::array<std::uint32_t, 3> s = {bits(r[1], 24, 8), bits(r[3], 0, 8), bits(r[3], 8, 8)};
    const std::array<std::uint32_t, 3> c = {bits(r[3], 16, 8), bits(r[3], 24, 8), bits(r[4], 0, 8)};
    for (int a = 0; a < 3; ++a) {
        g.position[a] = dequantise(p[a], page.position_lo[a], page.position_step[a]);
        g.log_scale[a] = dequantise(s[a], page.log_scale_lo, page.log_scale_step);
        g.sh_dc[a] = (dequantise(c[a], page.colour_lo[a], page.colour_step[a]) - 0.5f) / kShC0;
    }
    g.opacity = float(bits(r[1], 16, 8)) / 255.0f;
    g.rotation = decode_rotation(r[2]);
    g.level = static_cast<std::uint8_t>(bits(r[4], 8, 2) + 1);
    g.coverage_min = decode_coverage(bits(r[4], 10, 11), page);
    g.coverage_max = decode_coverage(bits(r[4], 21, 11), page);
    return g;
}

void decode_compact_into(const CompactRecord& record, std::span<const std::uint32_t> sh_words, const CompactPage& page,
                         int sh_degree, SplatCloud& out, std::size_t i) {
    const CompactGaussian g = decode_compact(record, page);
    out.positions[i] = g.position;
    out.rotations[i] = g.rotation;
    out.log_scales[i] = g.log_scale;
    const double o = std::clamp(double(g.opacity), 1e-30, 1.0 - 1e-7);
    out.opacity_logits[i] = g.opacity > 0.0f ? static_cast<float>(std::log(o / (1.0 - o))) : -100.0f;
    out.sh_dc[i] = g.sh_dc;
    decode_compact_sh(sh_words, page, sh_degree,
                      std::span(out.sh_rest).subspan(i * out.sh_rest_stride(), out.sh_rest_stride()));
    out.lod_level[i] = g.level;
    out.coverage_min[i] = g.coverage_min;
    out.coverage_max[i] = g.coverage_max;
}

SplatCloud compact_round_trip(const SplatCloud& cloud, int sh_degree) {
    sh_degree = std::clamp(sh_degree, 0, kMaxShDegree);
    SplatCloud out;
    out.resize(cloud.size());
    out.set_sh_degree(sh_degree);
    std::vector<std::uint32_t> sh(compact_sh_words(sh_degree));
    for (std::size_t first = 0; first < cloud.size(); first += kCompactPageSize) {
        const CompactPage page = fit_compact_page(cloud, first, kCompactPageSize, sh_degree);
        for (std::size_t i = first; i < std::min(first + kCompactPageSize, cloud.size()); ++i) {
            encode_compact_sh(cloud, i, page, sh_degree, sh);
            decode_compact_into(encode_compact(cloud, i, page), sh, page, sh_degree, out, i);
        }
    }
    return out;
}

}  // namespace splat_lod
