// The bake's differentiable rasteriser (docs/algorithms.md §1 and §4 step 7): its forward against the
// reference renderer, its backward against central differences, the chain rule to the stored
// parameters, determinism across thread counts, and the §7 hard cases that concern it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_io.h"
#include "splat_raster.h"
#include "splat_reference_test_helpers.h"
#include "splat_test_data.h"
#include "test_support.h"

namespace bake = splat_lod::bake;
namespace ref = splat_lod::reference;
using namespace splat_lod::reference::test;

namespace {

const glm::dvec3 kBackground(0.1, 0.2, 0.3);

// Gaussians in front of axis_camera(); `log_scale_min` sets their smallest size, so how much they overlap.
splat_lod::SplatCloud random_cloud(std::size_t n, unsigned seed, int sh_degree, float log_scale_min = -4.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), u01(0.0f, 1.0f);
    splat_lod::SplatCloud cloud;
    cloud.set_sh_degree(sh_degree);
    cloud.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const float z = -2.0f - 2.0f * u01(rng);
        cloud.positions[i] = {unit(rng) * 0.35f * -z, unit(rng) * 0.3f * -z, z};
        cloud.rotations[i] = {unit(rng), unit(rng), unit(rng), unit(rng)};
        const float spread = -1.5f - log_scale_min;
        cloud.log_scales[i] = {log_scale_min + spread * u01(rng), log_scale_min + spread * u01(rng),
                               log_scale_min + spread * u01(rng)};
        cloud.opacity_logits[i] = logit(0.05 + 0.9 * u01(rng));
        cloud.sh_dc[i] = {unit(rng), unit(rng), unit(rng)};
        for (std::size_t k = 0; k < cloud.sh_rest_stride(); ++k)
            cloud.sh_rest[i * cloud.sh_rest_stride() + k] = 0.3f * unit(rng);
    }
    return cloud;
}

std::vector<std::uint32_t> all_indices(const splat_lod::SplatCloud& cloud) {
    std::vector<std::uint32_t> indices(cloud.size());
    std::iota(indices.begin(), indices.end(), 0u);
    return indices;
}

bake::RasterFrame frame_for(const splat_lod::SplatCloud& cloud, const ref::ReferenceCamera& camera) {
    return {bake::project_for_raster(cloud, all_indices(cloud), camera, {}), camera.width, camera.height};
}

double max_difference(const bake::RasterImage& raster, const ref::ReferenceImage& reference) {
    EXPECT_EQ(raster.rgb.size(), reference.rgb.size());
    EXPECT_EQ(raster.transmittance.size(), reference.alpha.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < raster.rgb.size(); ++i)
        worst = std::max(worst, std::abs(raster.rgb[i] - reference.rgb[i]));
    for (std::size_t i = 0; i < raster.transmittance.size(); ++i)
        worst = std::max(worst, std::abs((1.0 - raster.transmittance[i]) - reference.alpha[i]));
    return worst;
}

ref::ReferenceImage reference_image(const splat_lod::SplatCloud& cloud, const ref::ReferenceCamera& camera) {
    ref::ReferenceSettings settings;
    settings.background = kBackground;
    return render_cloud(cloud, camera, settings);
}

// The per-pixel blend pattern written the slow way (every splat, no tiles): for each pixel, the
// splats it blends, whether each is at the 0.99 clamp, and whether the transmittance stop ended the
// list. A finite difference is only a derivative where this pattern is the same on both sides of
// the step (§4.7 holds it fixed).
constexpr std::size_t kPixelEnd = static_cast<std::size_t>(-1);
constexpr std::size_t kPixelStopped = static_cast<std::size_t>(-2);
std::vector<std::size_t> blend_pattern(const bake::RasterFrame& frame, const std::vector<double>& opacity) {
    std::vector<std::size_t> pattern;
    for (int y = 0; y < frame.height(); ++y)
        for (int x = 0; x < frame.width(); ++x) {
            double t = 1.0;
            std::size_t end = kPixelEnd;
            for (std::size_t i = 0; i < frame.splats().size(); ++i) {
                const bake::RasterSplat& s = frame.splats()[i];
                if (x < s.pixels.x0 || x > s.pixels.x1 || y < s.pixels.y0 || y > s.pixels.y1) continue;
                const glm::dvec2 d = glm::dvec2(x + 0.5, y + 0.5) - s.mean;
                const double g =
                    std::exp(-0.5 * (s.conic.x * d.x * d.x + 2.0 * s.conic.y * d.x * d.y + s.conic.z * d.y * d.y));
                const double alpha = std::min(0.99, opacity[i] * g);
                if (alpha < 1.0 / 255.0) continue;
                if (t * (1.0 - alpha) < 1e-4) {
                    end = kPixelStopped;
                    break;
                }
                t *= 1.0 - alpha;
                pattern.push_back(2 * i + (opacity[i] * g >= 0.99 ? 1 : 0));
            }
            pattern.push_back(end);
        }
    return pattern;
}

// L = ½ Σ (C − target)², as a sum of per-pixel terms so that differences of two losses can be
// taken pixel by pixel (the pixels a step does not touch then cancel exactly).
std::vector<double> pixel_losses(const bake::RasterImage& image, const std::vector<double>& target) {
    std::vector<double> losses(image.transmittance.size(), 0.0);
    for (std::size_t i = 0; i < image.rgb.size(); ++i)
        losses[i / 3] += 0.5 * (image.rgb[i] - target[i]) * (image.rgb[i] - target[i]);
    return losses;
}

double loss_difference(const std::vector<double>& plus, const std::vector<double>& minus) {
    double sum = 0.0;
    for (std::size_t p = 0; p < plus.size(); ++p) sum += plus[p] - minus[p];
    return sum;
}

struct Gradients {
    std::vector<glm::dvec3> colour;
    std::vector<double> opacity;
};

Gradients backward(const bake::RasterFrame& frame, const std::vector<glm::dvec3>& colour,
                   const std::vector<double>& opacity, const std::vector<double>& target, int threads = 1) {
    const auto image = bake::render_forward(frame, colour, opacity, kBackground, threads);
    std::vector<double> dl_drgb(image.rgb.size());
    for (std::size_t i = 0; i < dl_drgb.size(); ++i) dl_drgb[i] = image.rgb[i] - target[i];
    Gradients g{std::vector<glm::dvec3>(colour.size()), std::vector<double>(opacity.size())};
    bake::render_backward(frame, colour, opacity, kBackground, dl_drgb, g.colour, g.opacity, threads);
    return g;
}

std::vector<double> random_target(const bake::RasterFrame& frame, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    std::vector<double> target(3 * static_cast<std::size_t>(frame.width()) * static_cast<std::size_t>(frame.height()));
    for (double& v : target) v = u01(rng);
    return target;
}

// Central differences agree with the analytic value within 1e−6 relative (measured: 2.4e−8 at
// worst), with an absolute floor of 1e−10 for gradients that are zero.
constexpr double kStep = 1e-6;
::testing::AssertionResult matches_difference(double analytic, double difference, const char* what, std::size_t i) {
    if (std::abs(analytic - difference) <= 1e-6 * std::abs(difference) + 1e-10) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << what << " of splat " << i << ": analytic " << analytic
                                         << ", central difference " << difference;
}

}  // namespace

TEST(BakeRaster, ForwardEqualsTheReferenceOnRandomScenes) {
    struct Case {
        std::size_t n;
        unsigned seed;
        int sh_degree;
        int width, height;
    };
    for (const Case c : {Case{60, 1, 0, 64, 48}, Case{300, 2, 3, 50, 37}, Case{150, 3, 1, 17, 70}}) {
        const auto cloud = random_cloud(c.n, c.seed, c.sh_degree);
        const auto camera = axis_camera(c.width, c.height, 60.0);
        const bake::RasterFrame frame = frame_for(cloud, camera);
        EXPECT_GT(frame.splats().size(), c.n / 2);
        const auto image = bake::render_forward(frame, frame.colours(), frame.opacities(), kBackground);
        EXPECT_LE(max_difference(image, reference_image(cloud, camera)), 1e-12) << "seed " << c.seed;
    }
}

TEST(BakeRaster, ForwardEqualsTheReferenceOnARealCapture) {
    ENGINE_REQUIRE_DATA("splats/playcanvas-engine/biker.compressed.ply");
    const auto scene = engine::test::real_splat_scenes().front();  // the biker
    if (!std::filesystem::exists(scene.path)) GTEST_SKIP() << scene.path << " not found";
    const splat_lod::SplatCloud cloud = splat_lod::load_splat_file(scene.path);
    const auto view = engine::test::orbit_cameras(cloud, scene.up, 1, 80, 60).front();
    const ref::ReferenceCamera camera = ref::make_reference_camera(view);
    const bake::RasterFrame frame = frame_for(cloud, camera);
    EXPECT_GT(frame.splats().size(), cloud.size() / 4);
    const auto image = bake::render_forward(frame, frame.colours(), frame.opacities(), kBackground);
    EXPECT_LE(max_difference(image, reference_image(cloud, camera)), 1e-12);
}

TEST(BakeRaster, ProjectForRasterKeepsTheDrawnGaussiansWithTheirIndices) {
    const auto cloud = random_cloud(200, 4, 1);
    const auto camera = axis_camera(40, 30, 60.0);
    const std::vector<std::uint32_t> indices{7, 3, 150, 3, 199};
    const auto splats = bake::project_for_raster(cloud, indices, camera, {});
    std::vector<ref::ProjectedGaussian> expected;
    std::vector<std::uint32_t> expected_ids;
    for (const std::uint32_t i : indices) {
        const auto g = ref::project_gaussian(cloud, i, glm::dmat4(1.0), camera, {});
        if (!g.drawn()) continue;
        expected.push_back(g);
        expected_ids.push_back(i);
    }
    ASSERT_GE(expected.size(), 3u);
    ASSERT_EQ(splats.size(), expected.size());
    for (std::size_t k = 0; k < splats.size(); ++k) {
        EXPECT_EQ(splats[k].id, expected_ids[k]);
        EXPECT_EQ(splats[k].mean, expected[k].mean);
        EXPECT_EQ(splats[k].conic, expected[k].conic);
        EXPECT_EQ(splats[k].colour, expected[k].colour);
        EXPECT_EQ(splats[k].opacity, expected[k].opacity);
        EXPECT_EQ(splats[k].depth, expected[k].depth);
    }
    const std::vector<std::uint32_t> bad{200};
    EXPECT_THROW(bake::project_for_raster(cloud, bad, camera, {}), engine::Error);
}

TEST(BakeRaster, EqualDepthsAreOrderedById) {
    std::vector<bake::RasterSplat> splats(3);
    for (std::uint32_t i = 0; i < 3; ++i) {
        splats[i].id = 9 - i;
        splats[i].depth = 2.0;
        splats[i].pixels = {0, 0, 3, 3};
    }
    const bake::RasterFrame frame(splats, 4, 4);
    EXPECT_EQ(frame.splats()[0].id, 7u);
    EXPECT_EQ(frame.splats()[2].id, 9u);
}

TEST(BakeRaster, BackwardMatchesCentralDifferences) {
    splat_lod::SplatCloud cloud = random_cloud(36, 5, 0, -3.2f);
    // On the optical axis of the odd-sized image: its mean is a pixel centre, where α is clamped.
    add_gaussian(cloud, {0.0f, 0.0f, -2.5f}, -2.5f, 0.995, {0.9, 0.2, 0.4});
    // A stack in front of one spot, deep enough to reach the transmittance stop.
    for (int k = 0; k < 8; ++k)
        add_gaussian(cloud, {0.3f, 0.2f, -2.0f - 0.01f * static_cast<float>(k)}, -2.8f, 0.8, {0.3, 0.6, 0.1 * k});
    const bake::RasterFrame frame = frame_for(cloud, axis_camera(47, 39, 60.0));
    const auto colour = frame.colours();
    const auto opacity = frame.opacities();
    const auto target = random_target(frame, 6);
    const Gradients analytic = backward(frame, colour, opacity, target);
    const auto pattern = blend_pattern(frame, opacity);
    EXPECT_TRUE(std::any_of(pattern.begin(), pattern.end(), [](std::size_t v) {
        return v < kPixelStopped && v % 2 == 1;
    })) << "no pixel at the 0.99 clamp";
    EXPECT_GT(std::count(pattern.begin(), pattern.end(), kPixelStopped), 0)
        << "no pixel reaches the transmittance stop";

    std::size_t checked = 0, skipped = 0;
    for (std::size_t i = 0; i < colour.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            auto plus = colour, minus = colour;
            plus[i][c] += kStep;
            minus[i][c] -= kStep;
            const double difference =
                loss_difference(pixel_losses(bake::render_forward(frame, plus, opacity, kBackground, 1), target),
                                pixel_losses(bake::render_forward(frame, minus, opacity, kBackground, 1), target));
            EXPECT_TRUE(matches_difference(analytic.colour[i][c], difference / (2.0 * kStep), "dL/dcolour", i));
        }
        auto plus = opacity, minus = opacity;
        plus[i] += kStep;
        minus[i] -= kStep;
        if (blend_pattern(frame, plus) != pattern || blend_pattern(frame, minus) != pattern) {
            ++skipped;
            continue;
        }
        ++checked;
        const double difference =
            loss_difference(pixel_losses(bake::render_forward(frame, colour, plus, kBackground, 1), target),
                            pixel_losses(bake::render_forward(frame, colour, minus, kBackground, 1), target));
        EXPECT_TRUE(matches_difference(analytic.opacity[i], difference / (2.0 * kStep), "dL/dopacity", i));
    }
    EXPECT_GE(checked, colour.size() - 2);
    EXPECT_LE(skipped, 2u);
}

TEST(BakeRaster, ChainRuleReachesTheLogitAndTheDcCoefficients) {
    // Stored parameters in double: opacity = sigmoid(logit), colour = max(0, C0·dc + 0.5).
    const auto cloud = random_cloud(24, 8, 0, -3.0f);
    const bake::RasterFrame frame = frame_for(cloud, axis_camera(40, 32, 60.0));
    const std::size_t n = frame.splats().size();
    std::vector<double> logits(n);
    std::vector<glm::dvec3> dc(n);
    for (std::size_t i = 0; i < n; ++i) {
        logits[i] = cloud.opacity_logits[frame.splats()[i].id];
        dc[i] = glm::dvec3(cloud.sh_dc[frame.splats()[i].id]);
    }
    dc[0].x = -3.0;  // the red channel of one splat is clamped at 0: no gradient reaches its DC
    const auto activate = [&](const std::vector<double>& l, const std::vector<glm::dvec3>& d) {
        std::vector<double> opacity(n);
        std::vector<glm::dvec3> colour(n);
        for (std::size_t i = 0; i < n; ++i) {
            opacity[i] = 1.0 / (1.0 + std::exp(-l[i]));
            colour[i] = glm::max(kC0 * d[i] + 0.5, glm::dvec3(0.0));
        }
        return std::make_pair(colour, opacity);
    };
    const auto target = random_target(frame, 9);
    const auto [colour, opacity] = activate(logits, dc);
    const Gradients g = backward(frame, colour, opacity, target);
    const auto pattern = blend_pattern(frame, opacity);
    const auto loss_change = [&](const std::vector<double>& l_plus, const std::vector<glm::dvec3>& dc_plus,
                                 const std::vector<double>& l_minus, const std::vector<glm::dvec3>& dc_minus) {
        const auto [c_plus, o_plus] = activate(l_plus, dc_plus);
        const auto [c_minus, o_minus] = activate(l_minus, dc_minus);
        return loss_difference(pixel_losses(bake::render_forward(frame, c_plus, o_plus, kBackground, 1), target),
                               pixel_losses(bake::render_forward(frame, c_minus, o_minus, kBackground, 1), target)) /
               (2.0 * kStep);
    };
    std::size_t logits_checked = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 d_dc = bake::d_sh_dc_from_d_colour(g.colour[i], kC0 * dc[i] + 0.5);
        for (int c = 0; c < 3; ++c) {
            auto plus = dc, minus = dc;
            plus[i][c] += kStep;
            minus[i][c] -= kStep;
            EXPECT_TRUE(matches_difference(d_dc[c], loss_change(logits, plus, logits, minus), "dL/ddc", i));
        }
        auto plus = logits, minus = logits;
        plus[i] += kStep;
        minus[i] -= kStep;
        if (blend_pattern(frame, activate(plus, dc).second) != pattern ||
            blend_pattern(frame, activate(minus, dc).second) != pattern)
            continue;
        ++logits_checked;
        EXPECT_TRUE(matches_difference(bake::d_logit_from_d_opacity(g.opacity[i], logits[i]),
                                       loss_change(plus, dc, minus, dc), "dL/dlogit", i));
    }
    EXPECT_GE(logits_checked + 2, n);
    EXPECT_EQ(bake::d_sh_dc_from_d_colour({1.0, 1.0, 1.0}, {-0.1, 0.0, 0.2}), glm::dvec3(0.0, kC0, kC0));
    for (const double l : {-800.0, -60.0, 0.0, 9.2, 60.0, 800.0}) {
        const double d = bake::d_logit_from_d_opacity(1.0, l);
        EXPECT_TRUE(std::isfinite(d) && d >= 0.0 && d <= 0.25) << "logit " << l;
    }
    EXPECT_DOUBLE_EQ(bake::d_logit_from_d_opacity(2.0, 0.0), 0.5);
}

TEST(BakeRaster, ResultsDoNotDependOnTheThreadCount) {
    const auto cloud = random_cloud(400, 10, 1);
    const bake::RasterFrame frame = frame_for(cloud, axis_camera(96, 72, 80.0));
    const auto target = random_target(frame, 11);
    const auto image = bake::render_forward(frame, frame.colours(), frame.opacities(), kBackground, 1);
    const Gradients one = backward(frame, frame.colours(), frame.opacities(), target, 1);
    for (const int threads : {2, 3}) {
        const auto many = bake::render_forward(frame, frame.colours(), frame.opacities(), kBackground, threads);
        EXPECT_EQ(image.rgb, many.rgb);
        EXPECT_EQ(image.transmittance, many.transmittance);
        const Gradients g = backward(frame, frame.colours(), frame.opacities(), target, threads);
        EXPECT_EQ(one.colour, g.colour) << threads << " threads";
        EXPECT_EQ(one.opacity, g.opacity) << threads << " threads";
    }
}

TEST(BakeRaster, EmptyFrameRendersTheBackground) {
    const bake::RasterFrame frame({}, 5, 3);
    const auto image = bake::render_forward(frame, {}, {}, kBackground);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) EXPECT_EQ(image.colour_at(x, y), kBackground);
    EXPECT_EQ(image.transmittance, std::vector<double>(15, 1.0));
    const std::vector<double> dl_drgb(45, 1.0);
    EXPECT_NO_THROW(bake::render_backward(frame, {}, {}, kBackground, dl_drgb, {}, {}));
}

TEST(BakeRaster, OnePixelImageMatchesTheReferenceAndDifferentiates) {
    splat_lod::SplatCloud cloud;
    add_gaussian(cloud, {0.0f, 0.0f, -5.0f}, -1.0f, 0.6, {0.2, 0.5, 0.9});
    add_gaussian(cloud, {0.01f, 0.0f, -4.0f}, -1.5f, 0.4, {0.9, 0.1, 0.1});
    const auto camera = axis_camera(1, 1, 20.0);
    const bake::RasterFrame frame = frame_for(cloud, camera);
    ASSERT_EQ(frame.splats().size(), 2u);
    EXPECT_LE(max_difference(bake::render_forward(frame, frame.colours(), frame.opacities(), kBackground),
                             reference_image(cloud, camera)),
              1e-12);
    // L = ½|C|², so dL/dC = C, ∂C/∂c₀ = α₀ (T₀ = 1) and ∂C/∂c₁ = α₁(1 − α₀).
    const auto alpha = [&](std::size_t i) {
        const bake::RasterSplat& s = frame.splats()[i];
        const glm::dvec2 d = glm::dvec2(0.5) - s.mean;
        return std::min(0.99, s.opacity * std::exp(-0.5 * (s.conic.x * d.x * d.x + 2.0 * s.conic.y * d.x * d.y +
                                                           s.conic.z * d.y * d.y)));
    };
    const Gradients g = backward(frame, frame.colours(), frame.opacities(), {0.0, 0.0, 0.0});
    const glm::dvec3 c = bake::render_forward(frame, frame.colours(), frame.opacities(), kBackground).colour_at(0, 0);
    EXPECT_NEAR(glm::length(g.colour[0] - c * alpha(0)), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(g.colour[1] - c * (alpha(1) * (1.0 - alpha(0)))), 0.0, 1e-15);
}

TEST(BakeRaster, TenThousandCoincidentSplatsStopEarly) {
    splat_lod::SplatCloud cloud;
    for (int i = 0; i < 10000; ++i) add_gaussian(cloud, {0.0f, 0.0f, -5.0f}, -2.0f, 0.5, {0.8, 0.6, 0.4});
    const auto camera = axis_camera(33, 33);
    const bake::RasterFrame frame = frame_for(cloud, camera);
    ASSERT_EQ(frame.splats().size(), 10000u);
    const auto image = bake::render_forward(frame, frame.colours(), frame.opacities(), kBackground);
    EXPECT_LE(max_difference(image, reference_image(cloud, camera)), 1e-12);
    EXPECT_GE(image.transmittance[image.pixel_index(16, 16)], 1e-4);
    // dL/dC = 1 at the centre pixel only, where α = 0.5: 13 splats blend (0.5¹³ ≥ 1e−4 > 0.5¹⁴), the
    // other 9,987 are behind the stop and get no gradient.
    std::vector<double> dl_drgb(3 * 33 * 33, 0.0);
    std::fill_n(dl_drgb.begin() + static_cast<std::ptrdiff_t>(3 * image.pixel_index(16, 16)), 3, 1.0);
    std::vector<glm::dvec3> d_colour(frame.splats().size());
    std::vector<double> d_opacity(frame.splats().size());
    bake::render_backward(frame, frame.colours(), frame.opacities(), kBackground, dl_drgb, d_colour, d_opacity, 2);
    for (std::size_t i = 0; i < d_opacity.size(); ++i) {
        ASSERT_TRUE(std::isfinite(d_opacity[i]) && std::isfinite(d_colour[i].x)) << "splat " << i;
        ASSERT_EQ(d_colour[i] != glm::dvec3(0.0), i < 13) << "splat " << i;
    }
}

TEST(BakeRaster, OpacityAtTheClampHasNoOpacityGradient) {
    bake::RasterSplat splat;
    splat.mean = {0.5, 0.5};  // the centre of the only pixel: falloff exactly 1
    splat.conic = {1.0, 0.0, 1.0};
    splat.depth = 1.0;
    splat.pixels = {0, 0, 0, 0};
    const bake::RasterFrame frame({splat}, 1, 1);
    for (const double opacity : {0.99, 1.0}) {
        std::vector<glm::dvec3> d_colour(1);
        std::vector<double> d_opacity(1, 7.0);
        const std::vector<glm::dvec3> colour{{0.5, 0.5, 0.5}};
        const std::vector<double> opacities{opacity};
        const auto image = bake::render_forward(frame, colour, opacities, kBackground);
        EXPECT_NEAR(image.transmittance[0], 0.01, 1e-15);
        bake::render_backward(frame, colour, opacities, kBackground, std::vector<double>{1.0, 1.0, 1.0}, d_colour,
                              d_opacity);
        EXPECT_EQ(d_opacity[0], 0.0);
        EXPECT_DOUBLE_EQ(d_colour[0].x, 0.99);
    }
}

TEST(BakeRaster, RectanglesAreClippedToTheImage) {
    std::vector<bake::RasterSplat> splats(3);
    for (std::uint32_t i = 0; i < 3; ++i) {
        splats[i] = {{10.0, 5.0}, {0.05, 0.01, 0.05}, 0.7, {0.3, 0.4, 0.5}, 1.0 + i, i, {}};
    }
    splats[0].pixels = {-100, -100, 500, 500};  // larger than the image on every side
    splats[1].pixels = {30, 30, 40, 40};        // entirely outside
    splats[2].pixels = {8, 2, 4, 7};            // empty (x1 < x0)
    const bake::RasterFrame frame(splats, 20, 10);
    EXPECT_EQ(frame.splats()[0].pixels.x0, 0);
    EXPECT_EQ(frame.splats()[0].pixels.x1, 19);
    EXPECT_EQ(frame.splats()[0].pixels.y1, 9);
    for (std::size_t t = 0; t < frame.tile_count(); ++t)
        for (const bake::RasterTileEntry& e : frame.tile_entries(t)) EXPECT_EQ(e.splat, 0u);
    const Gradients g = backward(frame, frame.colours(), frame.opacities(), std::vector<double>(600, 0.0), 2);
    EXPECT_NE(g.opacity[0], 0.0);
    EXPECT_EQ(g.opacity[1], 0.0);
    EXPECT_EQ(g.colour[2], glm::dvec3(0.0));
}

TEST(BakeRaster, BadInputThrows) {
    bake::RasterSplat splat;
    splat.pixels = {0, 0, 1, 1};
    EXPECT_THROW(bake::RasterFrame({}, 0, 4), engine::Error);
    splat.mean.x = std::nan("");
    EXPECT_THROW(bake::RasterFrame({splat}, 4, 4), engine::Error);
    splat.mean.x = 1.0;
    const bake::RasterFrame frame({splat}, 4, 4);
    const std::vector<glm::dvec3> colour{{0.5, 0.5, 0.5}};
    EXPECT_THROW(bake::render_forward(frame, colour, {}, kBackground), engine::Error);
    EXPECT_THROW(bake::render_forward(frame, colour, std::vector<double>{INFINITY}, kBackground), engine::Error);
    std::vector<glm::dvec3> d_colour(1);
    std::vector<double> d_opacity(1);
    EXPECT_THROW(bake::render_backward(frame, colour, std::vector<double>{0.5}, kBackground, std::vector<double>(47),
                                       d_colour, d_opacity),
                 engine::Error);
}
