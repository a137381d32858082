// The docs/algorithms.md §7 hard cases that concern rendering, one test each, on the CPU reference renderer:
// no NaN in any output pixel, bad input dropped and counted, the documented behaviour asserted.
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_reference_test_helpers.h"

namespace ref = splat_lod::reference;
using namespace splat_lod::reference::test;

namespace {

const glm::dvec3 kGrey(0.8, 0.6, 0.4);

// One Gaussian at (0, 0, −5) in front of axis_camera(33, 33): its mean is the centre of pixel 16.
splat_lod::SplatCloud centred(float log_scale = -2.0f, double opacity = 0.8) {
    splat_lod::SplatCloud cloud;
    add_gaussian(cloud, {0.0f, 0.0f, -5.0f}, log_scale, opacity, kGrey);
    return cloud;
}

ref::ReferenceImage render_checked(const splat_lod::SplatCloud& cloud, const ref::ReferenceCamera& camera,
                                   ref::ReferenceStats& stats, const ref::ReferenceSettings& settings = {}) {
    auto image = render_cloud(cloud, camera, settings, &stats);
    EXPECT_TRUE(all_finite(image));
    EXPECT_TRUE(stats_add_up(stats));
    return image;
}

}  // namespace

TEST(ReferenceHardCases, LogScaleMinus30IsADilatedPoint) {
    ref::ReferenceStats stats;
    const auto cloud = centred(-30.0f, 0.8);
    const auto image = render_checked(cloud, axis_camera(33, 33), stats);
    EXPECT_EQ(stats.drawn, 1u);
    const double o = sigmoid(cloud.opacity_logits[0]);
    EXPECT_NEAR(image.alpha_at(16, 16), o, 1e-12);  // Σ2D = 0.3·I, peak α = opacity
    EXPECT_NEAR(image.alpha_at(17, 16), o * std::exp(-0.5 / 0.3), 1e-12);
}

TEST(ReferenceHardCases, LogScalePlus12CoversTheImageEvenly) {
    ref::ReferenceStats stats;
    const auto cloud = centred(12.0f, 0.5);
    const auto image = render_checked(cloud, axis_camera(33, 33), stats);
    EXPECT_EQ(stats.drawn, 1u);
    const glm::dvec3 expected = dc_colour(cloud.sh_dc[0]) * sigmoid(cloud.opacity_logits[0]);
    for (const glm::ivec2 p : {glm::ivec2(0, 0), glm::ivec2(16, 16), glm::ivec2(32, 5), glm::ivec2(3, 32)})
        EXPECT_NEAR(glm::length(image.colour_at(p.x, p.y) - expected), 0.0, 1e-9);
}

TEST(ReferenceHardCases, Anisotropy1e6ToOneIsAThinLine) {
    splat_lod::SplatCloud cloud = centred();
    cloud.log_scales[0] = {std::log(0.5f), std::log(0.5e-6f), std::log(0.5e-6f)};
    const double angle = 0.5;  // about the view axis
    cloud.rotations[0] = {float(std::cos(angle / 2)), 0.0f, 0.0f, float(std::sin(angle / 2))};
    ref::ReferenceStats stats;
    const auto image = render_checked(cloud, axis_camera(33, 33), stats);
    ASSERT_EQ(stats.drawn, 1u);
    const auto g = ref::project_gaussian(cloud, 0, glm::dmat4(1.0), axis_camera(33, 33), {});
    const double long2 = std::pow(100.0 * std::exp(double(cloud.log_scales[0].x)) / 5.0, 2.0);
    const double thin2 = std::pow(100.0 * std::exp(double(cloud.log_scales[0].y)) / 5.0, 2.0);
    const double det = g.cov2d.x * g.cov2d.z - g.cov2d.y * g.cov2d.y;
    EXPECT_NEAR(det / ((long2 + 0.3) * (thin2 + 0.3)), 1.0, 1e-9);
    // Along the line (up-right in the image: y points down) bright, across it dark.
    const glm::dvec2 along(std::cos(angle), -std::sin(angle)), across(-along.y, along.x);
    const glm::ivec2 on = glm::ivec2(glm::round(glm::dvec2(16.0) + 6.0 * along));
    const glm::ivec2 off = glm::ivec2(glm::round(glm::dvec2(16.0) + 4.0 * across));
    EXPECT_GT(image.alpha_at(on.x, on.y), 0.3);
    EXPECT_EQ(image.alpha_at(off.x, off.y), 0.0);
}

TEST(ReferenceHardCases, ZeroQuaternionIsDroppedAndCounted) {
    splat_lod::SplatCloud cloud = centred();
    cloud.rotations[0] = {0.0f, 0.0f, 0.0f, 0.0f};
    ref::ReferenceStats stats;
    const auto image = render_checked(cloud, axis_camera(33, 33), stats);
    EXPECT_EQ(stats.zero_rotation_dropped, 1u);
    EXPECT_TRUE(is_background(image, glm::dvec3(0.0)));
}

TEST(ReferenceHardCases, NonUnitQuaternionIsNormalised) {
    splat_lod::SplatCloud unit = centred(), scaled = centred();
    unit.log_scales[0] = scaled.log_scales[0] = {-1.5f, -3.0f, -2.0f};
    const float n = std::sqrt(14.0f);
    unit.rotations[0] = {3.0f / n, 1.0f / n, 0.0f, 2.0f / n};
    scaled.rotations[0] = {30.0f, 10.0f, 0.0f, 20.0f};
    const auto camera = axis_camera(33, 33);
    const auto a = render_cloud(unit, camera), b = render_cloud(scaled, camera);
    for (std::size_t i = 0; i < a.rgb.size(); ++i) ASSERT_NEAR(a.rgb[i], b.rgb[i], 1e-6);
}

TEST(ReferenceHardCases, OpacityLogitPlusMinus60) {
    splat_lod::SplatCloud cloud = centred();
    cloud.opacity_logits[0] = 60.0f;
    ref::ReferenceStats stats;
    auto image = render_checked(cloud, axis_camera(33, 33), stats);
    EXPECT_EQ(stats.drawn, 1u);
    EXPECT_DOUBLE_EQ(image.alpha_at(16, 16), 0.99);  // opacity 1, α capped at 0.99
    cloud.opacity_logits[0] = -60.0f;
    image = render_checked(cloud, axis_camera(33, 33), stats);
    EXPECT_EQ(stats.culled_invisible, 1u);
    EXPECT_TRUE(is_background(image, glm::dvec3(0.0)));
}

TEST(ReferenceHardCases, OpacityBelowOneOver255IsNeverVisible) {
    ref::ReferenceStats stats;
    auto image = render_checked(centred(-2.0f, 1.0 / 300.0), axis_camera(33, 33), stats);
    EXPECT_EQ(stats.culled_invisible, 1u);
    EXPECT_TRUE(is_background(image, glm::dvec3(0.0)));
    // Just above the threshold: drawn, over a tiny extent sqrt(2·ln(255·o)·Σxx).
    const auto faint = centred(-2.0f, 1.0 / 250.0);
    image = render_checked(faint, axis_camera(33, 33), stats);
    EXPECT_EQ(stats.drawn, 1u);
    const auto g = ref::project_gaussian(faint, 0, glm::dmat4(1.0), axis_camera(33, 33), {});
    EXPECT_LT(g.extent.x, 1.0);
    EXPECT_EQ(image.contributors_at(16, 16), 1u);
    EXPECT_EQ(image.contributors_at(17, 16), 0u);
}

TEST(ReferenceHardCases, NonFiniteValuesInEveryAttributeAreDroppedAndCounted) {
    splat_lod::SplatCloud clean = centred();
    clean.set_sh_degree(3);
    add_gaussian(clean, {0.1f, 0.0f, -4.0f}, -2.0f, 0.9, {0.1, 0.9, 0.1});  // the one made bad, in front
    const auto camera = axis_camera(33, 33);
    splat_lod::SplatCloud good_only = clean;
    good_only.keep_only({1, 0});
    const auto expected = render_cloud(good_only, camera);
    using Poison = std::function<void(splat_lod::SplatCloud&, float)>;
    std::vector<std::pair<std::string, Poison>> attributes;
    for (int c = 0; c < 3; ++c) {
        attributes.push_back({"position", [c](auto& s, float v) { s.positions[1][c] = v; }});
        attributes.push_back({"log_scale", [c](auto& s, float v) { s.log_scales[1][c] = v; }});
        attributes.push_back({"sh_dc", [c](auto& s, float v) { s.sh_dc[1][c] = v; }});
    }
    attributes.push_back({"rotation.w", [](auto& s, float v) { s.rotations[1].w = v; }});
    attributes.push_back({"rotation.z", [](auto& s, float v) { s.rotations[1].z = v; }});
    attributes.push_back({"opacity", [](auto& s, float v) { s.opacity_logits[1] = v; }});
    for (const int k : {1, 8, 15})
        attributes.push_back({"sh_rest", [k](auto& s, float v) { s.sh_rest_at(1, k, 2) = v; }});
    const float inf = std::numeric_limits<float>::infinity();
    for (const auto& [name, poison] : attributes)
        for (const float bad : {std::numeric_limits<float>::quiet_NaN(), inf, -inf}) {
            splat_lod::SplatCloud cloud = clean;
            poison(cloud, bad);
            ref::ReferenceStats stats;
            const auto image = render_checked(cloud, camera, stats);
            EXPECT_EQ(stats.non_finite_dropped, 1u) << name << " = " << bad;
            EXPECT_EQ(stats.drawn, 1u) << name << " = " << bad;
            EXPECT_EQ(image.rgb, expected.rgb) << name << " = " << bad;
        }
    // A degree cap does not let a poisoned coefficient through: "anywhere" means anywhere.
    splat_lod::SplatCloud capped = clean;
    capped.sh_rest_at(1, 15, 0) = inf;
    ref::ReferenceSettings degree0;
    degree0.sh_degree_cap = 0;
    ref::ReferenceStats stats;
    render_checked(capped, camera, stats, degree0);
    EXPECT_EQ(stats.non_finite_dropped, 1u);
}

TEST(ReferenceHardCases, NonFiniteOrSingularModelMatrixDropsTheInstance) {
    const auto cloud = centred();
    glm::dmat4 model(1.0);
    model[3][0] = std::numeric_limits<double>::quiet_NaN();
    ref::ReferenceStats stats;
    auto image = render_cloud(cloud, axis_camera(9, 9), {}, &stats, model);
    EXPECT_EQ(stats.non_finite_dropped, 1u);
    EXPECT_TRUE(is_background(image, glm::dvec3(0.0)));
    image = render_cloud(cloud, axis_camera(9, 9), {}, &stats, glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 0.0, 1.0)));
    EXPECT_EQ(stats.culled_degenerate, 1u);
    EXPECT_TRUE(is_background(image, glm::dvec3(0.0)));
}

TEST(ReferenceHardCases, NearPlaneCameraCentreAndBehindAreCulled) {
    ref::ReferenceSettings settings;
    settings.znear = 0.25;  // exactly representable, like the position below
    for (const glm::vec3 p : {glm::vec3(0, 0, -0.25f), glm::vec3(0.0f), glm::vec3(0, 0, 3), glm::vec3(1, 2, 0.5f)}) {
        splat_lod::SplatCloud cloud;
        add_gaussian(cloud, p, 1.0f, 0.9, kGrey);  // large: it would cover the image if drawn
        ref::ReferenceStats stats;
        const auto image = render_checked(cloud, axis_camera(33, 33), stats, settings);
        EXPECT_EQ(stats.culled_near, 1u) << p.z;
        EXPECT_TRUE(is_background(image, glm::dvec3(0.0)));
    }
    splat_lod::SplatCloud just_in_front;
    add_gaussian(just_in_front, {0, 0, -0.26f}, -3.0f, 0.9, kGrey);
    ref::ReferenceStats stats;
    const auto image = render_checked(just_in_front, axis_camera(33, 33), stats, settings);
    EXPECT_EQ(stats.drawn, 1u);
    EXPECT_GT(image.alpha_at(16, 16), 0.5);
}

TEST(ReferenceHardCases, GaussianAtAMillionUnits) {
    // 1e6 away along the axis with scale 1e4: σ = f·s/z = 1 px, the closed form still holds.
    splat_lod::SplatCloud far;
    add_gaussian(far, {0.0f, 0.0f, -1e6f}, std::log(1e4f), 0.8, kGrey);
    ref::ReferenceStats stats;
    const auto image = render_checked(far, axis_camera(33, 33), stats);
    const double sigma2 = std::pow(100.0 * std::exp(double(far.log_scales[0].x)) / 1e6, 2.0);
    EXPECT_NEAR(image.alpha_at(18, 16), sigmoid(far.opacity_logits[0]) * std::exp(-2.0 / (sigma2 + 0.3)), 1e-9);
    // Far off to the side: outside; and a camera itself at 1e6 sees a Gaussian 5 units ahead.
    splat_lod::SplatCloud side;
    add_gaussian(side, {1e6f, 0.0f, -1.0f}, 0.0f, 0.8, kGrey);
    render_checked(side, axis_camera(33, 33), stats);
    EXPECT_EQ(stats.culled_outside, 1u);
    auto camera = axis_camera(33, 33);
    camera.view = glm::translate(glm::dmat4(1.0), glm::dvec3(-1e6, -1e6, 0.0));
    camera.position = {1e6, 1e6, 0.0};
    splat_lod::SplatCloud there = centred();
    there.positions[0] = {1e6f, 1e6f, -5.0f};
    const auto moved = render_checked(there, camera, stats);
    EXPECT_NEAR(moved.alpha_at(16, 16), render_cloud(centred(), axis_camera(33, 33)).alpha_at(16, 16), 1e-12);
}

TEST(ReferenceHardCases, TenThousandCoincidentGaussiansStopEarly) {
    splat_lod::SplatCloud cloud;
    for (int i = 0; i < 10000; ++i) add_gaussian(cloud, {0.0f, 0.0f, -5.0f}, -3.0f, 0.5, kGrey);
    ref::ReferenceStats stats;
    const auto image = render_checked(cloud, axis_camera(33, 33), stats);
    EXPECT_EQ(stats.drawn, 10000u);
    // α = 0.5 at the centre: T = 0.5^n, and 0.5^14 < 1e−4 ≤ 0.5^13, so 13 splats are blended.
    EXPECT_EQ(image.contributors_at(16, 16), 13u);
    EXPECT_NEAR(image.alpha_at(16, 16), 1.0 - std::pow(0.5, 13), 1e-12);
    const glm::dvec3 c = dc_colour(cloud.sh_dc[0]);
    EXPECT_NEAR(glm::length(image.colour_at(16, 16) - c * (1.0 - std::pow(0.5, 13))), 0.0, 1e-12);
}

TEST(ReferenceHardCases, EqualDepthsAreOrderedByIndexDeterministically) {
    const glm::dvec3 red(1, 0, 0), green(0, 1, 0);
    splat_lod::SplatCloud cloud;
    add_gaussian(cloud, {0.0f, 0.0f, -5.0f}, -2.0f, 0.6, red);
    add_gaussian(cloud, {0.05f, 0.0f, -5.0f}, -2.0f, 0.6, green);
    const auto camera = axis_camera(33, 33);
    const auto a = render_cloud(cloud, camera), b = render_cloud(cloud, camera);
    EXPECT_EQ(a.rgb, b.rgb);
    // Both at depth 5 exactly: index 0 (red) is in front.
    const auto g0 = ref::project_gaussian(cloud, 0, glm::dmat4(1.0), camera, {});
    const auto g1 = ref::project_gaussian(cloud, 1, glm::dmat4(1.0), camera, {});
    ASSERT_EQ(g0.depth, g1.depth);
    const auto alpha = [](const ref::ProjectedGaussian& g) { return alpha_at_pixel(g, 16, 16); };
    const glm::dvec3 expected = g0.colour * alpha(g0) + g1.colour * alpha(g1) * (1.0 - alpha(g0));
    EXPECT_NEAR(glm::length(a.colour_at(16, 16) - expected), 0.0, 1e-12);
    // Across instances, the instance order breaks the tie: green's cloud first puts green in front.
    splat_lod::SplatCloud red_only = cloud, green_only = cloud;
    red_only.keep_only({1, 0});
    green_only.keep_only({0, 1});
    const std::vector<ref::ReferenceInstance> instances{{&green_only, glm::dmat4(1.0)}, {&red_only, glm::dmat4(1.0)}};
    const auto c = ref::render_reference(instances, camera, {});
    const glm::dvec3 swapped = g1.colour * alpha(g1) + g0.colour * alpha(g0) * (1.0 - alpha(g1));
    EXPECT_NEAR(glm::length(c.colour_at(16, 16) - swapped), 0.0, 1e-12);
}

TEST(ReferenceHardCases, DeterminantNotPositiveAfterProjectionIsCulled) {
    // A flat disc (y scale exp(−1000) = 0 in double) seen exactly edge-on: Σ2D has rank 1.
    splat_lod::SplatCloud cloud = centred(-1.0f);
    cloud.log_scales[0].y = -1000.0f;
    ref::ReferenceSettings no_dilation;
    no_dilation.dilation = 0.0;
    ref::ReferenceStats stats;
    auto image = render_checked(cloud, axis_camera(33, 33), stats, no_dilation);
    EXPECT_EQ(stats.culled_degenerate, 1u);
    EXPECT_TRUE(is_background(image, glm::dvec3(0.0)));
    // The 0.3 px dilation makes the same disc a drawable line.
    image = render_checked(cloud, axis_camera(33, 33), stats);
    EXPECT_EQ(stats.drawn, 1u);
    EXPECT_GT(image.alpha_at(16, 16), 0.5);
}

TEST(ReferenceHardCases, OneByOneAndWideTargets) {
    ref::ReferenceStats stats;
    const auto cloud = centred(-3.0f, 0.7);
    auto camera = axis_camera(1, 1, 1.0);
    const auto tiny = render_checked(cloud, camera, stats);
    EXPECT_NEAR(tiny.alpha_at(0, 0), sigmoid(cloud.opacity_logits[0]), 1e-12);  // the mean is the pixel centre
    camera = axis_camera(4096, 1, 1000.0);
    const auto wide = render_checked(cloud, camera, stats);
    EXPECT_EQ(stats.drawn, 1u);
    EXPECT_GT(wide.alpha_at(2047, 0), 0.3);
    EXPECT_EQ(wide.alpha_at(2047, 0), wide.alpha_at(2048, 0));  // mean at x = 2048, symmetric
    EXPECT_EQ(wide.alpha_at(0, 0), 0.0);
}

TEST(ReferenceHardCases, EmptySceneIsTheBackground) {
    ref::ReferenceSettings settings;
    settings.background = {0.25, 0.5, 0.75};
    ref::ReferenceStats stats;
    const auto none = ref::render_reference({}, axis_camera(20, 10), settings, nullptr, &stats);
    EXPECT_TRUE(is_background(none, settings.background));
    EXPECT_EQ(stats.considered, 0u);
    const splat_lod::SplatCloud empty;
    const std::vector<ref::ReferenceInstance> instances{{nullptr, glm::dmat4(1.0)}, {&empty, glm::dmat4(1.0)}};
    EXPECT_TRUE(is_background(ref::render_reference(instances, axis_camera(20, 10), settings, nullptr, &stats),
                              settings.background));
    EXPECT_EQ(stats.considered, 0u);
}

TEST(ReferenceHardCases, InvalidCameraSettingsOrMeshLayerAreAClearError) {
    EXPECT_THROW(ref::render_reference({}, axis_camera(0, 10), {}), engine::Error);
    auto camera = axis_camera(10, 10);
    camera.fx = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(ref::render_reference({}, camera, {}), engine::Error);
    ref::ReferenceSettings negative;
    negative.dilation = -0.3;
    EXPECT_THROW(ref::render_reference({}, axis_camera(10, 10), negative), engine::Error);
    const ref::MeshLayer wrong{5, 5, std::vector<double>(25), std::vector<glm::dvec3>(25)};
    try {
        ref::render_reference({}, axis_camera(10, 10), {}, &wrong);
        FAIL();
    } catch (const engine::Error& e) {
        EXPECT_NE(std::string(e.what()).find("render_reference(): mesh layer is 5x5"), std::string::npos) << e.what();
    }
}

TEST(ReferenceHardCases, MeshInFrontOfHalfTheImageHidesTheSplats) {
    const int w = 40, h = 20;
    ref::MeshLayer mesh{w, h, {}, {}};
    const glm::dvec3 surface(0.2, 0.4, 0.6), background(0.1, 0.1, 0.1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            mesh.depth.push_back(x < w / 2 ? 3.0 : std::numeric_limits<double>::infinity());
            mesh.colour.push_back(x < w / 2 ? surface : background);
        }
    splat_lod::SplatCloud cloud;
    add_gaussian(cloud, {0.0f, 0.0f, -5.0f}, 3.0f, 0.7, kGrey);        // behind the mesh, covers everything
    add_gaussian(cloud, {-0.1f, 0.0f, -2.0f}, -3.5f, 0.6, {1, 0, 0});  // in front of it, left of centre
    const std::vector<ref::ReferenceInstance> instances{{&cloud, glm::dmat4(1.0)}};
    const auto image = ref::render_reference(instances, axis_camera(w, h), {}, &mesh);
    EXPECT_TRUE(all_finite(image));
    const auto far = ref::project_gaussian(cloud, 0, glm::dmat4(1.0), axis_camera(w, h), {});
    const auto near = ref::project_gaussian(cloud, 1, glm::dmat4(1.0), axis_camera(w, h), {});
    EXPECT_EQ(image.colour_at(2, 2), surface);  // only the mesh
    EXPECT_EQ(image.contributors_at(2, 2), 0u);
    const double a_far = alpha_at_pixel(far, 37, 2);
    EXPECT_NEAR(glm::length(image.colour_at(37, 2) - (far.colour * a_far + (1.0 - a_far) * background)), 0.0, 1e-12);
    // The near splat composites over the mesh colour: C + T·mesh_colour.
    const glm::ivec2 p(glm::floor(near.mean));
    ASSERT_LT(p.x, w / 2);
    const double a = alpha_at_pixel(near, p.x, p.y);
    EXPECT_NEAR(glm::length(image.colour_at(p.x, p.y) - (near.colour * a + (1.0 - a) * surface)), 0.0, 1e-12);
    EXPECT_EQ(image.contributors_at(p.x, p.y), 1u);
}
