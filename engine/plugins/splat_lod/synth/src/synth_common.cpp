// The synth RNG and the helpers every builder shares.
#include "splat_lod/synth/synth_common.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <glm/glm.hpp>

#include "engine/core/error.h"

namespace splat_lod::synth {

// ---- Rng ------------------------------------------------------------------------------------

namespace {

std::uint64_t splitmix64(std::uint64_t& x) {
    x += 0x9e3779b97f4a7c15ull;
    std::uint64_t z = x;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

std::uint64_t rotl(std::uint64_t x, int k) {
    return (x << k) | (x >> (64 - k));
}

}  // namespace

Rng::Rng(std::uint64_t seed, std::uint64_t stream) {
    std::uint64_t stream_state = stream;
    std::uint64_t x = seed ^ splitmix64(stream_state);
    // splitmix64 is a bijection of a counter, so at most one of the four words is zero and
    // xoshiro's all-zero state cannot occur.
    for (auto& word : state_) word = splitmix64(x);
}

std::uint64_t Rng::next_u64() {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
}

float Rng::uniform() {
    return static_cast<float>(next_u64() >> 40) * 0x1.0p-24f;
}

float Rng::uniform(float lo, float hi) {
    return lo + (hi - lo) * uniform();
}

int Rng::uniform_int(int lo, int hi) {
    const std::uint64_t span = static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo) + 1;
    return lo + static_cast<int>(((next_u64() >> 32) * span) >> 32);
}

float Rng::normal() {
    // One draw per statement: the order in which operands of + are evaluated is unspecified, and
    // the sum's rounding depends on which draw lands where.
    float sum = uniform();
    for (int i = 0; i < 3; ++i) sum += uniform();
    return (sum - 2.0f) * 1.7320508075688772f;  // the sum has variance 4/12
}

bool Rng::chance(float probability) {
    return uniform() < probability;
}

// ---- Platform-independent transcendental functions ------------------------------------------

SinCos sin_cos(double angle) {
    // Reduce to r in [-π/4, π/4] and the quadrant; π/2 in two parts keeps r accurate for the
    // angles of a few turns used here.
    constexpr double kHalfPiHi = 1.5707963267341256;
    constexpr double kHalfPiLo = 6.077100506506192e-11;
    const double quadrant = std::floor(angle * (2.0 / kPi) + 0.5);
    const double r = (angle - quadrant * kHalfPiHi) - quadrant * kHalfPiLo;
    const double r2 = r * r;
    // Taylor series to r^15 / r^16 in Horner form: the first omitted term is below 5e-17 for
    // |r| <= π/4. Factorials up to 16! are exact in double.
    double sin_r = 0.0, cos_r = 0.0;
    double sin_factorial = 1307674368000.0;   // 15!
    double cos_factorial = 20922789888000.0;  // 16!
    for (int k = 7; k >= 0; --k) {
        const double sign = (k % 2 == 0) ? 1.0 : -1.0;
        sin_r = sin_r * r2 + sign / sin_factorial;
        cos_r = cos_r * r2 + ((k + 1) % 2 == 0 ? 1.0 : -1.0) / cos_factorial;
        if (k == 0) break;
        sin_factorial /= (2.0 * k + 1.0) * (2.0 * k);
        cos_factorial /= (2.0 * k + 2.0) * (2.0 * k + 1.0);
    }
    cos_r = cos_r * r2 + 1.0;
    sin_r *= r;
    const auto q = static_cast<long long>(quadrant) & 3;
    switch (q) {
        case 0:
            return {static_cast<float>(sin_r), static_cast<float>(cos_r)};
        case 1:
            return {static_cast<float>(cos_r), static_cast<float>(-sin_r)};
        case 2:
            return {static_cast<float>(-sin_r), static_cast<float>(-cos_r)};
        default:
            return {static_cast<float>(-cos_r), static_cast<float>(sin_r)};
    }
}

double log_det(double x) {
    // x = m · 2^e with m in [√½, √2); log m = 2 atanh(s), s = (m − 1)/(m + 1), |s| <= 0.172, so the
    // odd series to s^19 is exact to double precision.
    int exponent = 0;
    double m = std::frexp(x, &exponent);
    if (m < 0.70710678118654752) {
        m *= 2.0;
        --exponent;
    }
    const double s = (m - 1.0) / (m + 1.0);
    const double s2 = s * s;
    double series = 1.0 / 19.0;
    for (int k = 17; k >= 1; k -= 2) series = series * s2 + 1.0 / k;
    constexpr double kLn2 = 0.69314718055994530942;
    return exponent * kLn2 + 2.0 * s * series;
}

// ---- Gaussians and frames -------------------------------------------------------------------

namespace {

glm::dvec3 unit(const glm::dvec3& v) {
    return v / std::sqrt(glm::dot(v, v));
}

}  // namespace

Rotation rotation_from_axes(const glm::vec3& axis_x, const glm::vec3& axis_y) {
    // Gram–Schmidt first, so that float rounding in the callers' frames cannot skew the matrix;
    // then the matrix → quaternion conversion on its largest diagonal term (Shepperd), which
    // needs only sqrt and stays accurate for every rotation.
    const glm::dvec3 x = unit(glm::dvec3(axis_x));
    const glm::dvec3 y = unit(glm::dvec3(axis_y) - glm::dot(glm::dvec3(axis_y), x) * x);
    const glm::dvec3 z = glm::cross(x, y);
    // m[row][column] with columns x, y, z.
    const double m00 = x.x, m10 = x.y, m20 = x.z, m01 = y.x, m11 = y.y, m21 = y.z, m02 = z.x, m12 = z.y, m22 = z.z;
    const double trace = m00 + m11 + m22;
    double w, qx, qy, qz;
    if (trace > 0.0) {
        const double s = 2.0 * std::sqrt(trace + 1.0);
        w = 0.25 * s, qx = (m21 - m12) / s, qy = (m02 - m20) / s, qz = (m10 - m01) / s;
    } else if (m00 > m11 && m00 > m22) {
        const double s = 2.0 * std::sqrt(1.0 + m00 - m11 - m22);
        w = (m21 - m12) / s, qx = 0.25 * s, qy = (m01 + m10) / s, qz = (m02 + m20) / s;
    } else if (m11 > m22) {
        const double s = 2.0 * std::sqrt(1.0 + m11 - m00 - m22);
        w = (m02 - m20) / s, qx = (m01 + m10) / s, qy = 0.25 * s, qz = (m12 + m21) / s;
    } else {
        const double s = 2.0 * std::sqrt(1.0 + m22 - m00 - m11);
        w = (m10 - m01) / s, qx = (m02 + m20) / s, qy = (m12 + m21) / s, qz = 0.25 * s;
    }
    const double norm = std::sqrt(w * w + qx * qx + qy * qy + qz * qz);
    return {static_cast<float>(w / norm), static_cast<float>(qx / norm), static_cast<float>(qy / norm),
            static_cast<float>(qz / norm)};
}

void append_gaussian(SplatCloud& cloud, const GaussianDraft& g) {
    cloud.positions.push_back(g.position);
    cloud.rotations.push_back(rotation_from_axes(g.axis_x, g.axis_y));
    cloud.log_scales.emplace_back(static_cast<float>(log_det(g.scale.x)), static_cast<float>(log_det(g.scale.y)),
                                  static_cast<float>(log_det(g.scale.z)));
    cloud.opacity_logits.push_back(g.opacity_logit);
    cloud.sh_dc.push_back((clamp_rgb(g.rgb) - glm::vec3(0.5f)) / kShC0);
    cloud.sh_rest.resize(cloud.sh_rest.size() + cloud.sh_rest_stride(), 0.0f);
    cloud.lod_level.push_back(1);
    cloud.coverage_min.push_back(-1.0f);
    cloud.coverage_max.push_back(-1.0f);
    for (auto& extra : cloud.extras) extra.values.push_back(0.0f);
}

glm::vec3 random_unit_vector(Rng& rng) {
    for (;;) {
        glm::vec3 v;
        v.x = rng.uniform(-1.0f, 1.0f);
        v.y = rng.uniform(-1.0f, 1.0f);
        v.z = rng.uniform(-1.0f, 1.0f);
        const float length2 = glm::dot(v, v);
        // The lower bound keeps the direction well defined after normalising.
        if (length2 > 1e-4f && length2 <= 1.0f) return v / std::sqrt(length2);
    }
}

glm::vec3 any_perpendicular(const glm::vec3& n) {
    const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 p = glm::cross(n, helper);
    return p / std::sqrt(glm::dot(p, p));
}

glm::vec3 random_perpendicular(const glm::vec3& n, Rng& rng) {
    const glm::vec3 a = any_perpendicular(n);
    const glm::vec3 b = glm::cross(n, a);
    for (;;) {
        const float u = rng.uniform(-1.0f, 1.0f), v = rng.uniform(-1.0f, 1.0f);
        const float length2 = u * u + v * v;
        if (length2 > 1e-4f && length2 <= 1.0f) {
            const glm::vec3 p = a * u + b * v;
            return p / std::sqrt(glm::dot(p, p));
        }
    }
}

// ---- Noise and colour -----------------------------------------------------------------------

namespace {

float lattice_value(std::int64_t x, std::int64_t y, std::int64_t z, std::uint64_t seed) {
    std::uint64_t h = seed ^ (static_cast<std::uint64_t>(x) * 0x8da6b343ull) ^
                      (static_cast<std::uint64_t>(y) * 0xd8163841ull) ^ (static_cast<std::uint64_t>(z) * 0xcb1ab31full);
    return static_cast<float>(splitmix64(h) >> 40) * 0x1.0p-24f;
}

float smooth(float t) {
    return t * t * (3.0f - 2.0f * t);
}

float lerp(float a, float b, float t) {
    return a + (b - a) * t;
}

}  // namespace

float value_noise_3d(const glm::vec3& p, std::uint64_t seed) {
    const glm::vec3 cell(std::floor(p.x), std::floor(p.y), std::floor(p.z));
    const glm::vec3 f = p - cell;
    const auto x = static_cast<std::int64_t>(cell.x), y = static_cast<std::int64_t>(cell.y),
               z = static_cast<std::int64_t>(cell.z);
    const float sx = smooth(f.x), sy = smooth(f.y), sz = smooth(f.z);
    float plane[2];
    for (int k = 0; k < 2; ++k) {
        const float bottom = lerp(lattice_value(x, y, z + k, seed), lattice_value(x + 1, y, z + k, seed), sx);
        const float top = lerp(lattice_value(x, y + 1, z + k, seed), lattice_value(x + 1, y + 1, z + k, seed), sx);
        plane[k] = lerp(bottom, top, sy);
    }
    return lerp(plane[0], plane[1], sz);
}

float value_noise(float x, float z, std::uint64_t seed) {
    return value_noise_3d(glm::vec3(x, 0.0f, z), seed);
}

glm::vec3 clamp_rgb(const glm::vec3& rgb) {
    return glm::clamp(rgb, glm::vec3(0.0f), glm::vec3(1.0f));
}

glm::vec3 mix_rgb(const glm::vec3& a, const glm::vec3& b, float t) {
    return a + (b - a) * t;
}

float sun_shade(const glm::vec3& normal, float ambient) {
    const float lit = std::max(0.0f, glm::dot(normal, kSunDirection));
    return ambient + (1.0f - ambient) * lit;
}

// ---- Argument checks ------------------------------------------------------------------------

std::string number_text(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", static_cast<double>(v));
    return text;
}

void require_finite(const glm::vec3& v, const char* builder, const char* what) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        engine::fail(std::string("splat_lod::synth::") + builder + "(): " + what + " is not finite");
}

void require_positive(float v, const char* builder, const char* what) {
    if (!(std::isfinite(v) && v > 0.0f))
        engine::fail(std::string("splat_lod::synth::") + builder + "(): " + what + " must be a positive number, got " +
                     number_text(v));
}

void require_detail(float detail, const char* builder) {
    if (!(std::isfinite(detail) && detail >= kMinDetail && detail <= kMaxDetail))
        engine::fail(std::string("splat_lod::synth::") + builder + "(): detail must be in [" + number_text(kMinDetail) +
                     ", " + number_text(kMaxDetail) + "], got " + number_text(detail));
}

void require_count(double expected_gaussians, const char* builder) {
    if (!(expected_gaussians <= kMaxBuilderGaussians))
        engine::fail(std::string("splat_lod::synth::") + builder + "(): the arguments ask for about " +
                     number_text(static_cast<float>(expected_gaussians)) + " Gaussians, more than the " +
                     number_text(static_cast<float>(kMaxBuilderGaussians)) + " one builder call may append");
}

}  // namespace splat_lod::synth
