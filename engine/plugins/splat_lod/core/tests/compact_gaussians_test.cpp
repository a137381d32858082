// The compact resident format (splat_lod/core/compact_gaussians.h): every field of the record round
// trips within its stated bound, on ordinary and hard values (the SH bands: compact_sh_test.cpp).
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "splat_lod/core/compact_gaussians.h"
#include "splat_lod/core/gaussian_extent.h"

namespace {

using splat_lod::CompactGaussian;
using splat_lod::CompactPage;
using splat_lod::SplatCloud;

SplatCloud random_cloud(std::size_t n, int sh_degree, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    SplatCloud c;
    c.resize(n);
    c.set_sh_degree(sh_degree);
    for (std::size_t i = 0; i < n; ++i) {
        c.positions[i] = glm::vec3(u(rng) * 10.0f, u(rng) * 2.0f, 5.0f + u(rng));
        c.rotations[i] = {u(rng), u(rng), u(rng), u(rng)};
        c.log_scales[i] = glm::vec3(-4.0f + 2.0f * u(rng), -3.0f + u(rng), -6.0f + u(rng));
        c.opacity_logits[i] = 3.0f * u(rng);
        c.sh_dc[i] = glm::vec3(u(rng), 1.5f * u(rng), 0.2f * u(rng));
        for (float& v : std::span(c.sh_rest).subspan(i * c.sh_rest_stride(), c.sh_rest_stride())) v = 0.3f * u(rng);
        c.lod_level[i] = static_cast<std::uint8_t>(1 + i % 4);
        c.coverage_min[i] = std::exp2(6.0f * u(rng));
        c.coverage_max[i] = c.coverage_min[i] * 8.0f;
    }
    return c;
}

CompactGaussian round_trip(const SplatCloud& c, std::size_t i, const CompactPage& page) {
    return splat_lod::decode_compact(splat_lod::encode_compact(c, i, page), page);
}

// The angle between two rotations (radians), from their unit quaternions.
double rotation_angle(const splat_lod::Rotation& a, const splat_lod::Rotation& b) {
    const double na = std::sqrt(double(a.w) * a.w + a.x * a.x + a.y * a.y + a.z * a.z);
    const double dot = (double(a.w) * b.w + double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z) / na;
    return 2.0 * std::acos(std::min(1.0, std::abs(dot)));
}

// Three components at 10 bits over [−1/√2, 1/√2] are each off by at most e = 1/(1023·√2); the
// largest, recomputed from them, by at most 3e (it is the largest, so |∂w/∂v| ≤ 1 for each). The
// quaternion is off by at most √(3e² + 9e²) = √12·e and the rotation angle by twice that:
// 4.8e-3 rad, 0.27°.
const double kRotationBound = 2.0 * std::sqrt(12.0) / (1023.0 * std::sqrt(2.0)) * 1.01;

TEST(CompactGaussians, EveryFieldRoundTripsWithinHalfItsStep) {
    const SplatCloud c = random_cloud(256, 3, 1);
    const CompactPage page = splat_lod::fit_compact_page(c, 0, 256, 3);
    for (std::size_t i = 0; i < c.size(); ++i) {
        const CompactGaussian g = round_trip(c, i, page);
        for (int a = 0; a < 3; ++a) {
            EXPECT_LE(std::abs(g.position[a] - c.positions[i][a]), 0.5f * page.position_step[a] * 1.001f + 1e-6f);
            EXPECT_LE(std::abs(g.log_scale[a] - c.log_scales[i][a]), 0.5f * page.log_scale_step * 1.001f + 1e-6f);
            const float colour = splat_lod::kShC0 * c.sh_dc[i][a] + 0.5f;
            EXPECT_LE(std::abs(splat_lod::kShC0 * g.sh_dc[a] + 0.5f - colour),
                      0.5f * page.colour_step[a] * 1.001f + 1e-6f);
        }
        const double opacity = splat_lod::world::opacity_from_logit(c.opacity_logits[i]);
        EXPECT_LE(std::abs(g.opacity - opacity), 0.5 / 255.0 + 1e-6);
        EXPECT_LE(rotation_angle(c.rotations[i], g.rotation), kRotationBound);
        EXPECT_EQ(g.level, c.lod_level[i]);
        EXPECT_LE(std::abs(std::log2(g.coverage_min / c.coverage_min[i])), 0.5f * page.coverage_step * 1.001f + 1e-6f);
        EXPECT_LE(std::abs(std::log2(g.coverage_max / c.coverage_max[i])), 0.5f * page.coverage_step * 1.001f + 1e-6f);
    }
    // The steps are the ranges over their codes: a page of 20 m in x has 20/65535 m steps.
    EXPECT_NEAR(page.position_step.x, 20.0f / 65535.0f, 0.01f * 20.0f / 65535.0f);
    EXPECT_EQ(sizeof(splat_lod::CompactRecord), 20u);
}

TEST(CompactGaussians, EndsOfEveryRangeAreExact) {
    SplatCloud c = random_cloud(3, 0, 2);
    c.positions = {glm::vec3(-1.0f, 2.0f, 3.0f), glm::vec3(1.0f, 4.0f, 3.0f), glm::vec3(0.0f, 3.0f, 3.0f)};
    c.opacity_logits = {100.0f, -100.0f, 0.0f};  // opacity 1, 0, ½
    const CompactPage page = splat_lod::fit_compact_page(c, 0, 3, 0);
    const CompactGaussian lo = round_trip(c, 0, page), hi = round_trip(c, 1, page), mid = round_trip(c, 2, page);
    EXPECT_EQ(lo.position, c.positions[0]);
    EXPECT_NEAR(hi.position.x, 1.0f, 1e-6f);
    EXPECT_NEAR(hi.position.y, 4.0f, 1e-6f);
    EXPECT_EQ(hi.position.z, 3.0f);  // a zero-width range decodes to its one value exactly
    EXPECT_EQ(lo.opacity, 1.0f);
    EXPECT_EQ(hi.opacity, 0.0f);  // never drawn
    EXPECT_NEAR(mid.opacity, 128.0f / 255.0f, 1e-7f);
    const splat_lod::CompactRecord r = splat_lod::encode_compact(c, 1, page);
    EXPECT_EQ(r[0], 0xFFFFFFFFu);         // x and y at the top of their ranges
    EXPECT_EQ(r[1] & 0xFFFFu, 0u);        // z: the range's only value
    EXPECT_EQ((r[1] >> 16) & 0xFFu, 0u);  // opacity 0
}

TEST(CompactGaussians, HardCasesStayBoundedAndFinite) {
    SplatCloud c;
    c.resize(6);
    // Tiny and huge scales in one page: the log range is wide, every decoded scale still within its step.
    c.log_scales = {glm::vec3(-25.0f), glm::vec3(9.0f), glm::vec3(-25.0f, 9.0f, 0.0f),
                    glm::vec3(0.0f),   glm::vec3(0.0f), glm::vec3(0.0f)};
    // Near-degenerate rotations: the identity, a half turn (w = 0), two equal largest components, a
    // negative largest component and a quaternion far from unit length.
    c.rotations = {{1, 0, 0, 0},
                   {0, 1, 0, 0},
                   {0.7071068f, 0.7071068f, 0, 0},
                   {-0.9f, 0.1f, 0.3f, -0.2f},
                   {1e-6f, 3e-6f, 0, 0},
                   {0.5f, 0.5f, 0.5f, 0.5f}};
    c.opacity_logits = {0.0f, 0.0f, 0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f};
    const CompactPage page = splat_lod::fit_compact_page(c, 0, 6, 0);
    EXPECT_EQ(page.position_step, glm::vec3(0.0f));  // every mean the same: zero-width box
    for (std::size_t i = 0; i < c.size(); ++i) {
        const CompactGaussian g = round_trip(c, i, page);
        EXPECT_EQ(g.position, glm::vec3(0.0f));
        if (i == 3) {
            EXPECT_EQ(g.opacity, 0.0f) << "a NaN opacity is stored as never drawn";
            continue;
        }
        for (int a = 0; a < 3; ++a)
            EXPECT_LE(std::abs(g.log_scale[a] - c.log_scales[i][a]), 0.5f * 34.0f / 255.0f * 1.001f);
        EXPECT_LE(rotation_angle(c.rotations[i], g.rotation), kRotationBound) << "rotation " << i;
        const double norm = std::sqrt(double(g.rotation.w) * g.rotation.w + g.rotation.x * g.rotation.x +
                                      g.rotation.y * g.rotation.y + g.rotation.z * g.rotation.z);
        EXPECT_NEAR(norm, 1.0, 2e-3);
    }
}

TEST(CompactGaussians, CoverageBoundsKeepUnsetAndZero) {
    SplatCloud c = random_cloud(5, 0, 3);
    c.coverage_min = {-1.0f, 0.0f, 1e-6f, 1e6f, std::numeric_limits<float>::quiet_NaN()};
    c.coverage_max = {1e6f, -1.0f, 1e-6f, std::numeric_limits<float>::infinity(), -1.0f};
    const CompactPage page = splat_lod::fit_compact_page(c, 0, 5, 0);
    EXPECT_EQ(round_trip(c, 0, page).coverage_min, -1.0f);
    EXPECT_EQ(round_trip(c, 1, page).coverage_min, 0.0f);
    EXPECT_EQ(round_trip(c, 1, page).coverage_max, -1.0f);
    EXPECT_EQ(round_trip(c, 4, page).coverage_min, -1.0f) << "NaN is stored unset";
    // 1e-6 .. 1e6 is 40 octaves over 2045 steps: each bound within half a step in log2.
    for (std::size_t i : {2u, 3u})
        EXPECT_LE(std::abs(std::log2(round_trip(c, i, page).coverage_min / c.coverage_min[i])), 0.5f * 40.0f / 2045.0f);
    EXPECT_NEAR(std::log2(round_trip(c, 3, page).coverage_max), std::log2(1e6f), 1e-3f) << "+inf stored as the top";
}

TEST(CompactGaussians, RoundTripCloudIsDeterministicAndMatchesTheRecords) {
    const SplatCloud c = random_cloud(700, 2, 4);
    const SplatCloud a = splat_lod::compact_round_trip(c, 2), b = splat_lod::compact_round_trip(c, 2);
    ASSERT_EQ(a.size(), c.size());
    EXPECT_EQ(a.sh_degree, 2);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.sh_rest, b.sh_rest);
    // Gaussian 600 is in the third page, decoded against that page's ranges.
    const CompactPage page = splat_lod::fit_compact_page(c, 512, 256, 2);
    const CompactGaussian g = round_trip(c, 600, page);
    EXPECT_EQ(a.positions[600], g.position);
    EXPECT_EQ(a.lod_level[600], g.level);
    EXPECT_NEAR(splat_lod::world::opacity_from_logit(a.opacity_logits[600]), g.opacity, 1e-6);
    EXPECT_EQ(a.sh_rest[600 * a.sh_rest_stride()], b.sh_rest[600 * b.sh_rest_stride()]);
}

}  // namespace
