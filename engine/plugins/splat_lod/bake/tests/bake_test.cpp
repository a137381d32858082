// The LOD bake (docs/algorithms.md §4): each step on hand-made input with closed-form answers, the hard
// cases of §7, bad input, and small end-to-end bakes (determinism, order, what the levels hold).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>

#include "bake_steps.h"
#include "engine/core/error.h"
#include "splat_lod/bake/bake.h"
#include "splat_lod/bake/bake_cameras.h"
#include "splat_lod/core/splat_io.h"
#include "splat_raster.h"
#include "test_support.h"

namespace {

using namespace splat_lod;
using bake::detail::CoverageTable;

// A camera at `eye` looking at `target` (+y up), width × height, 50° vertical field of view.
reference::ReferenceCamera look_at(glm::dvec3 eye, glm::dvec3 target, int width = 128, int height = 128) {
    engine::CameraView view;
    view.view = glm::lookAt(glm::vec3(eye), glm::vec3(target), glm::vec3(0, 1, 0));
    view.width = width;
    view.height = height;
    view.fov_y = glm::radians(50.0f);
    return reference::make_reference_camera(view);
}

void add_gaussian(SplatCloud& cloud, glm::vec3 position, glm::vec3 scale, float opacity = 0.9f, Rotation rotation = {},
                  glm::vec3 rgb = glm::vec3(0.5f)) {
    const std::size_t i = cloud.size();
    cloud.resize(i + 1);
    cloud.positions[i] = position;
    cloud.log_scales[i] = glm::log(scale);
    cloud.opacity_logits[i] = std::log(opacity / (1.0f - opacity));
    cloud.rotations[i] = rotation;
    cloud.sh_dc[i] = (rgb - 0.5f) / kShC0;
}

// A small textured patch: n×n Gaussians on the z = 0 plane, spacing `step`, colours varying.
SplatCloud patch(int n, float step, float size) {
    SplatCloud cloud;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float u = (static_cast<float>(x) - 0.5f * static_cast<float>(n - 1)) * step;
            const float v = (static_cast<float>(y) - 0.5f * static_cast<float>(n - 1)) * step;
            const glm::vec3 rgb(0.5f + 0.4f * std::sin(static_cast<float>(x)),
                                0.5f + 0.4f * std::cos(static_cast<float>(y)), (x + y) % 2 ? 0.9f : 0.1f);
            add_gaussian(cloud, {u, v, 0.0f}, glm::vec3(size, size, size * 0.3f), 0.8f, {}, rgb);
        }
    return cloud;
}

std::vector<reference::ReferenceCamera> ring(int count, double distance, int width = 128, int height = 128) {
    std::vector<reference::ReferenceCamera> cameras;
    for (int i = 0; i < count; ++i) {
        const double a = 0.5 * (static_cast<double>(i) / std::max(1, count - 1) - 0.5);  // ±0.25 rad around +z
        cameras.push_back(
            look_at({distance * std::sin(a), 0.1 * distance, distance * std::cos(a)}, {0, 0, 0}, width, height));
    }
    return cameras;
}

TEST(BakeCoverage, AxisAlignedAnisotropicGaussianMatchesTheClosedForm) {
    // Seen straight on from distance d at the image centre: Σ2D = diag((f·sx/d)², (f·sy/d)²), and
    // the coverage is the shorter chord 2·sqrt(L)·min(f·sx, f·sy)/d with L = 2 ln(255·o).
    SplatCloud cloud;
    add_gaussian(cloud, {0, 0, 0}, {0.02f, 0.005f, 0.01f}, 0.6f);
    const double d = 3.0;
    const auto camera = look_at({0, 0, d}, {0, 0, 0});
    const double l = 2.0 * std::log(255.0 * 0.6);
    const double expected = 2.0 * std::sqrt(l) * camera.fx * 0.005 / d;
    EXPECT_NEAR(bake::detail::coverage_in_camera(cloud, 0, camera, 0.2), expected, 1e-4 * expected);
}

TEST(BakeCoverage, RotatedAnisotropicGaussianMatchesTheClosedForm) {
    // Rotated by θ about the view axis: Σ2D = R diag(a², b²) Rᵀ, whose inverse has
    // (Σ⁻¹)ₓₓ = cos²θ/a² + sin²θ/b² and (Σ⁻¹)ᵧᵧ = sin²θ/a² + cos²θ/b²; the chords are 2·sqrt(L/(Σ⁻¹)ᵢᵢ).
    const double theta = 0.6;
    SplatCloud cloud;
    add_gaussian(cloud, {0, 0, 0}, {0.03f, 0.004f, 0.01f}, 0.9f,
                 {static_cast<float>(std::cos(theta / 2)), 0.0f, 0.0f, static_cast<float>(std::sin(theta / 2))});
    const double d = 2.0;
    const auto camera = look_at({0, 0, d}, {0, 0, 0});
    const double a = camera.fx * 0.03 / d, b = camera.fx * 0.004 / d;
    const double c = std::cos(theta), s = std::sin(theta);
    const double inv_xx = c * c / (a * a) + s * s / (b * b), inv_yy = s * s / (a * a) + c * c / (b * b);
    const double l = 2.0 * std::log(255.0 * 0.9);
    const double expected = 2.0 * std::min(std::sqrt(l / inv_xx), std::sqrt(l / inv_yy));
    EXPECT_NEAR(bake::detail::coverage_in_camera(cloud, 0, camera, 0.2), expected, 1e-4 * expected);
}

TEST(BakeCoverage, InvisibleBehindAndOutsideAreNotSeen) {
    SplatCloud cloud;
    add_gaussian(cloud, {0, 0, 0}, glm::vec3(0.01f), 0.5f / 255.0f);  // opacity below 1/255
    add_gaussian(cloud, {0, 0, 5}, glm::vec3(0.01f));                 // behind the camera
    add_gaussian(cloud, {50, 0, 0}, glm::vec3(0.01f));                // centre outside the image
    add_gaussian(cloud, {0, 0, 2.9f}, glm::vec3(0.01f));              // inside znear
    add_gaussian(cloud, {0, 0, 0}, glm::vec3(1e-13f));                // far below a pixel: seen, tiny
    const auto camera = look_at({0, 0, 3}, {0, 0, 0});
    for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(bake::detail::coverage_in_camera(cloud, i, camera, 0.2), -1.0) << i;
    const double tiny = bake::detail::coverage_in_camera(cloud, 4, camera, 0.2);
    EXPECT_GE(tiny, 0.0);
    EXPECT_LT(tiny, 1e-6);
}

TEST(BakeSteps, PercentileInterpolatesBetweenOrderStatistics) {
    std::vector<double> v{4, 1, 3, 2, 5};
    EXPECT_DOUBLE_EQ(bake::detail::percentile(v, 10.0), 1.4);  // numpy: 1 + 0.4·(2 − 1)
    EXPECT_DOUBLE_EQ(bake::detail::percentile(v, 90.0), 4.6);
    EXPECT_DOUBLE_EQ(bake::detail::percentile(v, 50.0), 3.0);
    std::vector<double> one{7};
    EXPECT_DOUBLE_EQ(bake::detail::percentile(one, 90.0), 7.0);
    std::vector<double> none;
    EXPECT_DOUBLE_EQ(bake::detail::percentile(none, 50.0), -1.0);
}

TEST(BakeSteps, NormalisationIsContinuousAndBoundedFarAway) {
    bake::detail::Normaliser n;
    n.centre = {1, 2, 3};
    n.radius = 2.0;
    EXPECT_EQ(n.apply({1, 2, 3}), glm::dvec3(0.0));
    EXPECT_NEAR(n.apply({3, 2, 3}).x, 1.0, 1e-12);        // on the cube's face
    EXPECT_NEAR(n.apply({3.000002, 2, 3}).x, 1.0, 1e-5);  // continuous across it
    EXPECT_NEAR(n.apply({1e6, 2, 3}).x, 2.0, 1e-5);       // 1e6 units: near the outer face
    const glm::dvec3 far = n.apply({1e300, -1e300, 3});   // beyond double range when divided
    EXPECT_TRUE(std::isfinite(far.x) && std::isfinite(far.y));
    EXPECT_LE(std::abs(far.x), 2.0);
    // Symmetric, not one-sided (the contraction applies on every side).
    EXPECT_NEAR(n.apply({-1e6, 2, 3}).x, -2.0, 1e-5);
}

TEST(BakeSteps, SingleCameraTakesTheRadiusFromTheGaussians) {
    const SplatCloud cloud = patch(10, 0.1f, 0.02f);
    const auto n = bake::detail::make_normaliser({look_at({0, 0, 3}, {0, 0, 0})}, cloud);
    EXPECT_TRUE(n.from_gaussians);
    EXPECT_NEAR(n.radius, 0.5 * 0.9 * 0.98, 0.02);  // half the 1st–99th percentile span of the patch
    const auto two =
        bake::detail::make_normaliser({look_at({0, 0, 3}, {0, 0, 0}), look_at({1, 0, 3}, {0, 0, 0})}, cloud);
    EXPECT_FALSE(two.from_gaussians);
    EXPECT_NEAR(two.radius, 0.5, 1e-6);  // camera centres come from float matrices
}

TEST(BakeSteps, PoolingFlipsAntipodalQuaternionsAndAveragesActivatedOpacity) {
    SplatCloud cloud;
    const float h = std::sqrt(0.5f);
    add_gaussian(cloud, {0, 0, 0}, glm::vec3(0.01f), 0.9f, {h, 0, 0, h});
    add_gaussian(cloud, {1, 0, 0}, glm::vec3(0.04f), 0.5f, {-h, 0, 0, -h});  // the same rotation, negated
    cloud.resize(3);
    const std::vector<std::uint32_t> members{0, 1};
    bake::detail::pool(cloud, members, cloud, 2);
    const Rotation q = cloud.rotations[2];
    EXPECT_NEAR(std::abs(q.w), h, 1e-6);  // not cancelled to zero
    EXPECT_NEAR(std::abs(q.z), h, 1e-6);
    EXPECT_NEAR(q.w * q.z, 0.5, 1e-6);  // same sign: the first member's hemisphere
    EXPECT_NEAR(cloud.positions[2].x, 0.5f, 1e-6);
    EXPECT_NEAR(cloud.log_scales[2].x, 0.5 * (std::log(0.01) + std::log(0.04)), 1e-5);
    EXPECT_NEAR(1.0 / (1.0 + std::exp(-cloud.opacity_logits[2])), 0.7, 1e-5);
}

TEST(BakeSteps, PoolingClampsTheOpacityLogit) {
    SplatCloud cloud;
    add_gaussian(cloud, {0, 0, 0}, glm::vec3(0.01f));
    cloud.opacity_logits[0] = 60.0f;  // sigmoid = 1 in float: the mean must not become an infinite logit
    cloud.resize(2);
    const std::vector<std::uint32_t> one{0};
    bake::detail::pool(cloud, one, cloud, 1);
    EXPECT_NEAR(cloud.opacity_logits[1], std::log((1 - 1e-4) / 1e-4), 1e-3);
}

TEST(BakeSteps, EnlargementUsesTheMedianAndClamps) {
    CoverageTable table(3);
    SplatCloud cloud;
    add_gaussian(cloud, {0, 0, 0}, glm::vec3(0.01f));
    // Built by hand through the public interface: one Gaussian seen by three cameras.
    const auto camera = look_at({0, 0, 3}, {0, 0, 0});
    table.append(cloud, 0, {camera, camera, camera}, 0.2, 1);
    const double s = bake::detail::coverage_in_camera(cloud, 0, camera, 0.2);
    const std::vector<std::uint32_t> member{0};
    EXPECT_NEAR(bake::detail::mean_median_coverage(table, member, 4), s / 4, 1e-5 * s);  // one member: its median
    EXPECT_DOUBLE_EQ(bake::detail::enlargement(2.0, 0.5, 8.0), 4.0);
    EXPECT_DOUBLE_EQ(bake::detail::enlargement(2.0, 0.01, 8.0), 8.0);
    EXPECT_DOUBLE_EQ(bake::detail::enlargement(2.0, 5.0, 8.0), 1.0);
    EXPECT_DOUBLE_EQ(bake::detail::enlargement(2.0, 0.0, 8.0), 8.0);
}

TEST(BakeSteps, CellsAreAtLeastTheDistanceAdaptiveSize) {
    bake::BakeOptions options;
    const std::vector<reference::ReferenceCamera> cameras{look_at({0, 0, 3}, {0, 0, 0}, 512, 384)};
    bake::detail::Normaliser n;
    n.radius = 0.01;  // a tiny grid: the distance cells take over
    const auto a = bake::detail::cell_key({0.0, 0.0, 0.0}, 4, 100, n, cameras, options);
    const auto b = bake::detail::cell_key({0.001, 0.001, 0.0}, 4, 100, n, cameras, options);
    EXPECT_EQ(a, b);  // 1 mm apart at 3 m: one distance cell at scale 64
    options.cells = bake::CellRule::grid;
    EXPECT_NE(bake::detail::cell_key({0.0, 0.0, 0.0}, 4, 100, n, cameras, options),
              bake::detail::cell_key({0.001, 0.001, 0.0}, 4, 100, n, cameras, options));
}

bake::BakeOptions quick_options() {
    bake::BakeOptions options;
    options.refine_iterations = 20;
    options.refine_cameras = 4;
    options.threads = 2;
    return options;
}

TEST(Bake, BuildsCoarseLevelsFirstWithRangesAndLoadsBack) {
    const SplatCloud fine = patch(40, 0.01f, 0.004f);
    bake::BakeSummary summary;
    const auto cameras = ring(6, 1.0, 128, 128);
    const SplatCloud baked = bake::bake_lod(fine, cameras, quick_options(), &summary);
    ASSERT_GT(baked.size(), fine.size());
    EXPECT_EQ(summary.output_gaussians, baked.size());
    // Coarse levels first, then finer, never back.
    for (std::size_t i = 1; i < baked.size(); ++i) EXPECT_GE(baked.lod_level[i - 1], baked.lod_level[i]);
    std::size_t level1 = 0;
    for (std::size_t i = 0; i < baked.size(); ++i) {
        level1 += baked.lod_level[i] == 1;
        if (baked.coverage_min[i] >= 0.0f) {
            EXPECT_LE(baked.coverage_min[i], baked.coverage_max[i]);
        }
    }
    EXPECT_EQ(level1, fine.size());  // the fine model is kept whole
    for (const auto& level : summary.levels) {
        EXPECT_LE(level.added, level.small);
        if (level.added > 0) {
            EXPECT_EQ(level.refine_iterations, 20);
            EXPECT_GE(level.refine_psnr_after, level.refine_psnr_before - 0.5) << "level " << level.level;
        }
    }
    // Round trip through the LOD asset format.
    const auto path = engine::test::output_dir("Bake") / "patch.lod.ply";
    write_inria_ply(path, baked);
    const SplatCloud loaded = load_splat_file(path);
    ASSERT_EQ(loaded.size(), baked.size());
    EXPECT_EQ(loaded.lod_level, baked.lod_level);
    EXPECT_EQ(loaded.coverage_max, baked.coverage_max);
    // Without member ranges the levels' ranges overlap, and the asset says so.
    EXPECT_EQ(baked.level_handover, LevelHandover::overlapping);
    EXPECT_EQ(loaded.level_handover, LevelHandover::overlapping);
}

TEST(Bake, IsDeterministicForAnyThreadCount) {
    const SplatCloud fine = patch(24, 0.012f, 0.004f);
    const auto cameras = ring(4, 1.0, 128, 128);
    auto options = quick_options();
    options.threads = 1;
    const auto one = encode_inria_ply(bake::bake_lod(fine, cameras, options));
    options.threads = 2;
    const auto two = encode_inria_ply(bake::bake_lod(fine, cameras, options));
    EXPECT_EQ(one, two);
}

TEST(Bake, OneGaussianPerCellAndASingleCamera) {
    // Sparse Gaussians (one per cell) seen by one camera: B comes from the Gaussians, S_avg from one
    // member each, and every pooled Gaussian copies its member's colour.
    SplatCloud fine;
    for (int i = 0; i < 5; ++i)
        add_gaussian(fine, {0.3f * static_cast<float>(i - 2), 0, 0}, glm::vec3(0.001f), 0.9f, {}, {0.2f, 0.6f, 0.9f});
    auto options = quick_options();
    options.refine_iterations = 0;
    options.cells = bake::CellRule::grid;
    bake::BakeSummary summary;
    const SplatCloud baked = bake::bake_lod(fine, {look_at({0, 0, 2}, {0, 0, 0})}, options, &summary);
    EXPECT_TRUE(summary.radius_from_gaussians);
    ASSERT_FALSE(summary.levels.empty());
    EXPECT_EQ(summary.levels[0].added, 5u);
    for (std::size_t i = 0; i < baked.size(); ++i) EXPECT_NEAR(baked.sh_dc[i].x, fine.sh_dc[0].x, 1e-6);
}

TEST(Bake, NothingSmallAddsNothing) {
    SplatCloud fine;
    add_gaussian(fine, {0, 0, 0}, glm::vec3(0.5f));  // fills the view at every scale
    bake::BakeSummary summary;
    const SplatCloud baked = bake::bake_lod(fine, ring(3, 2.0), quick_options(), &summary);
    EXPECT_EQ(baked.size(), 1u);
    for (const auto& level : summary.levels) EXPECT_EQ(level.added, 0u);
    EXPECT_GT(baked.coverage_min[0], 0.0f);  // ranges are still measured
}

TEST(Bake, FarAwayAndUnseenGaussiansSurvive) {
    SplatCloud fine = patch(10, 0.02f, 0.004f);
    add_gaussian(fine, {1e6f, 0, -1e6f}, glm::vec3(0.01f));  // far outside every view
    bake::BakeSummary summary;
    const SplatCloud baked = bake::bake_lod(fine, ring(3, 1.0), quick_options(), &summary);
    EXPECT_GE(summary.unseen, 1u);
    for (std::size_t i = 0; i < baked.size(); ++i) {
        EXPECT_TRUE(std::isfinite(baked.positions[i].x));
        EXPECT_TRUE(std::isfinite(baked.opacity_logits[i]));
    }
}

TEST(Bake, BadInputGivesClearErrors) {
    const auto cameras = ring(2, 1.0);
    const auto expect_error = [](const auto& call, const std::string& part) {
        try {
            call();
            ADD_FAILURE() << "no error, expected one containing \"" << part << "\"";
        } catch (const engine::Error& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    expect_error([&] { bake::bake_lod(SplatCloud{}, cameras, quick_options()); }, "no Gaussians");
    expect_error([&] { bake::bake_lod(patch(3, 0.1f, 0.01f), {}, quick_options()); }, "no cameras");
    SplatCloud behind;
    add_gaussian(behind, {0, 0, 5}, glm::vec3(0.01f));
    expect_error([&] { bake::bake_lod(behind, cameras, quick_options()); }, "sees any");
    SplatCloud baked = patch(3, 0.1f, 0.01f);
    baked.lod_level[0] = 2;
    expect_error([&] { bake::bake_lod(baked, cameras, quick_options()); }, "already has LOD");
    auto options = quick_options();
    options.coarsest_level = 7;
    expect_error([&] { bake::validate(options); }, "coarsest level");
    expect_error([&] { bake::bake_camera_poses("missing_cameras.json", {}, {0, 1, 0}); }, "missing_cameras.json");
    expect_error([&] { bake::bake_camera_poses("rings:0x3", {}, {0, 1, 0}); }, "rings:");
}

TEST(BakeRefine, ParameterGradientsMatchFiniteDifferences) {
    // The refinement's chain with the geometry held fixed (as the refinement holds it): logit →
    // opacity → image and SH DC → colour → image, checked on the loss ½‖C − target‖² of a few
    // overlapping Gaussians against central differences in the stored parameters.
    SplatCloud cloud;
    add_gaussian(cloud, {0.00f, 0.00f, 0.0f}, glm::vec3(0.05f), 0.6f, {}, {0.8f, 0.3f, 0.2f});
    add_gaussian(cloud, {0.03f, 0.01f, 0.1f}, glm::vec3(0.04f), 0.5f, {}, {0.1f, 0.7f, 0.4f});
    add_gaussian(cloud, {-0.02f, 0.02f, -0.1f}, glm::vec3(0.06f), 0.7f, {}, {0.3f, 0.2f, 0.9f});
    const auto camera = look_at({0, 0, 1}, {0, 0, 0}, 24, 24);
    const std::vector<std::uint32_t> all{0, 1, 2};
    const bake::RasterFrame frame(bake::project_for_raster(cloud, all, camera, reference::ReferenceSettings{}, 1), 24,
                                  24);
    const std::vector<double> target(24 * 24 * 3, 0.4);
    const glm::dvec3 background(0.1);
    const std::size_t n = frame.splats().size();
    ASSERT_EQ(n, 3u);

    // Parameters per splat (in frame order): DC and logit, and the colour before the clamp.
    std::vector<glm::dvec3> dc(n);
    std::vector<double> logit(n);
    for (std::size_t j = 0; j < n; ++j) {
        dc[j] = glm::dvec3(cloud.sh_dc[frame.splats()[j].id]);
        logit[j] = cloud.opacity_logits[frame.splats()[j].id];
    }
    const auto before_clamp = [&](const std::vector<glm::dvec3>& d, std::size_t j) {
        return 0.5 + static_cast<double>(kShC0) * d[j];
    };
    const auto loss = [&](const std::vector<glm::dvec3>& d, const std::vector<double>& l) {
        std::vector<glm::dvec3> colour(n);
        std::vector<double> opacity(n);
        for (std::size_t j = 0; j < n; ++j) {
            colour[j] = glm::max(before_clamp(d, j), glm::dvec3(0.0));
            opacity[j] = 1.0 / (1.0 + std::exp(-l[j]));
        }
        const auto image = bake::render_forward(frame, colour, opacity, background, 1);
        double sum = 0.0;
        for (std::size_t p = 0; p < target.size(); ++p)
            sum += 0.5 * (image.rgb[p] - target[p]) * (image.rgb[p] - target[p]);
        return std::pair{sum, image};
    };
    std::vector<glm::dvec3> colour(n);
    std::vector<double> opacity(n);
    for (std::size_t j = 0; j < n; ++j) {
        colour[j] = glm::max(before_clamp(dc, j), glm::dvec3(0.0));
        opacity[j] = 1.0 / (1.0 + std::exp(-logit[j]));
    }
    const auto image = loss(dc, logit).second;
    std::vector<double> dl(target.size());
    for (std::size_t p = 0; p < dl.size(); ++p) dl[p] = image.rgb[p] - target[p];
    std::vector<glm::dvec3> d_colour(n);
    std::vector<double> d_opacity(n);
    bake::render_backward(frame, colour, opacity, background, dl, d_colour, d_opacity, 1);

    const double h = 1e-6;
    for (std::size_t j = 0; j < n; ++j) {
        const double analytic_logit = bake::d_logit_from_d_opacity(d_opacity[j], logit[j]);
        auto plus = logit, minus = logit;
        plus[j] += h;
        minus[j] -= h;
        const double numeric_logit = (loss(dc, plus).first - loss(dc, minus).first) / (2 * h);
        EXPECT_NEAR(analytic_logit, numeric_logit, 1e-5 * std::abs(numeric_logit) + 1e-8) << "logit of splat " << j;
        const glm::dvec3 analytic_dc = bake::d_sh_dc_from_d_colour(d_colour[j], before_clamp(dc, j));
        for (int c = 0; c < 3; ++c) {
            auto dc_plus = dc, dc_minus = dc;
            dc_plus[j][c] += h;
            dc_minus[j][c] -= h;
            const double numeric = (loss(dc_plus, logit).first - loss(dc_minus, logit).first) / (2 * h);
            EXPECT_NEAR(analytic_dc[c], numeric, 1e-5 * std::abs(numeric) + 1e-8) << "dc " << c << " of splat " << j;
        }
    }
}

}  // namespace
