// The CPU reference renderer against closed forms of docs/algorithms.md §1 and against a brute-force
// per-pixel loop written here. The §7 hard cases are in splat_reference_hard_cases_test.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.h"
#include "engine/render/camera.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_io.h"
#include "splat_reference_test_helpers.h"
#include "test_support.h"

namespace ref = splat_lod::reference;
using namespace splat_lod::reference::test;

namespace {

// §1 per pixel, written the slow way: every projected Gaussian, no bounding boxes, no tiles.
ref::ReferenceImage brute_force(const splat_lod::SplatCloud& cloud, const ref::ReferenceCamera& camera,
                                const ref::ReferenceSettings& settings) {
    std::vector<ref::ProjectedGaussian> drawn;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto g = ref::project_gaussian(cloud, i, glm::dmat4(1.0), camera, settings);
        if (g.drawn()) drawn.push_back(g);
    }
    std::stable_sort(drawn.begin(), drawn.end(), [](const auto& a, const auto& b) { return a.depth < b.depth; });
    ref::ReferenceImage image{camera.width, camera.height, {}, {}, {}};
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            double t = 1.0;
            glm::dvec3 c(0.0);
            std::uint32_t n = 0;
            for (const auto& g : drawn) {
                const double alpha = alpha_at_pixel(g, x, y);
                if (alpha < 1.0 / 255.0) continue;
                if (t * (1.0 - alpha) < 1e-4) break;
                c += g.colour * alpha * t;
                t *= 1.0 - alpha;
                ++n;
            }
            c += t * settings.background;
            image.rgb.insert(image.rgb.end(), {c.x, c.y, c.z});
            image.alpha.push_back(1.0 - t);
            image.contributors.push_back(n);
        }
    return image;
}

splat_lod::SplatCloud random_cloud(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), u01(0.0f, 1.0f);
    splat_lod::SplatCloud cloud;
    cloud.set_sh_degree(3);
    cloud.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const float z = -2.0f - 6.0f * u01(rng);
        cloud.positions[i] = {unit(rng) * 0.7f * -z, unit(rng) * 0.55f * -z, z};
        cloud.rotations[i] = {unit(rng), unit(rng), unit(rng), unit(rng)};
        cloud.log_scales[i] = {-4.0f + 3.0f * u01(rng), -4.0f + 3.0f * u01(rng), -4.0f + 3.0f * u01(rng)};
        cloud.opacity_logits[i] = logit(0.02 + 0.97 * u01(rng));
        cloud.sh_dc[i] = {unit(rng), unit(rng), unit(rng)};
        for (std::size_t k = 0; k < cloud.sh_rest_stride(); ++k)
            cloud.sh_rest[i * cloud.sh_rest_stride() + k] = 0.3f * unit(rng);
    }
    return cloud;
}

double max_difference(const ref::ReferenceImage& a, const ref::ReferenceImage& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) worst = std::max(worst, std::abs(a.rgb[i] - b.rgb[i]));
    for (std::size_t i = 0; i < a.alpha.size(); ++i) worst = std::max(worst, std::abs(a.alpha[i] - b.alpha[i]));
    return worst;
}

}  // namespace

TEST(ReferenceRenderer, IsotropicGaussianHasClosedFormPeakAndFalloff) {
    splat_lod::SplatCloud cloud;
    add_gaussian(cloud, {0.0f, 0.0f, -5.0f}, std::log(0.05f), 0.8, {0.9, 0.5, 0.2});
    const auto camera = axis_camera(101, 101, 100.0);  // centre (50.5, 50.5): the centre of pixel 50
    ref::ReferenceStats stats;
    const auto image = render_cloud(cloud, camera, {}, &stats);
    EXPECT_EQ(stats.drawn, 1u);

    const double sigma = 100.0 * std::exp(static_cast<double>(cloud.log_scales[0].x)) / 5.0;  // σ = f·s/z ≈ 1 px
    const double variance = sigma * sigma + 0.3;
    const double opacity = sigmoid(cloud.opacity_logits[0]);
    const glm::dvec3 colour = dc_colour(cloud.sh_dc[0]);
    for (int k = 0; k <= 8; ++k)
        for (const glm::ivec2 step : {glm::ivec2(1, 0), glm::ivec2(0, 1), glm::ivec2(1, 1), glm::ivec2(-1, 1)}) {
            const glm::ivec2 pixel = glm::ivec2(50) + k * step;
            const double r2 = double(k * k) * glm::dot(glm::dvec2(step), glm::dvec2(step));
            double alpha = std::min(0.99, opacity * std::exp(-0.5 * r2 / variance));
            if (alpha < 1.0 / 255.0) alpha = 0.0;
            const glm::dvec3 got = image.colour_at(pixel.x, pixel.y);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], colour[c] * alpha, 1e-12) << "pixel " << pixel.x << "," << pixel.y;
            EXPECT_NEAR(image.alpha_at(pixel.x, pixel.y), alpha, 1e-12);
        }
    const auto g = ref::project_gaussian(cloud, 0, glm::dmat4(1.0), camera, {});
    EXPECT_NEAR(g.cov2d.x, variance, 1e-12);
    EXPECT_NEAR(g.cov2d.y, 0.0, 1e-12);
    EXPECT_NEAR(g.extent.x, std::sqrt(2.0 * std::log(255.0 * opacity) * variance), 1e-12);
    EXPECT_DOUBLE_EQ(g.depth, 5.0);
}

TEST(ReferenceRenderer, MipFilterScalesOpacityByTheDeterminantRatio) {
    splat_lod::SplatCloud cloud;
    add_gaussian(cloud, {0.0f, 0.0f, -5.0f}, std::log(0.02f), 0.8, {0.9, 0.5, 0.2});
    ref::ReferenceSettings settings;
    settings.mip_filter = true;
    const auto g = ref::project_gaussian(cloud, 0, glm::dmat4(1.0), axis_camera(101, 101), settings);
    const double sigma2 = std::pow(100.0 * std::exp(double(cloud.log_scales[0].x)) / 5.0, 2.0);
    EXPECT_NEAR(g.opacity, sigmoid(cloud.opacity_logits[0]) * sigma2 / (sigma2 + 0.3), 1e-12);  // sqrt(σ⁴/(σ²+0.3)²)
}

TEST(ReferenceRenderer, CameraConventionsMatchCameraView) {
    const auto view =
        engine::make_look_at_camera({3, 2, 4}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), 160, 120, 0.1f, 100.0f);
    const auto camera = ref::make_reference_camera(view);
    EXPECT_DOUBLE_EQ(camera.fx, 60.0 / std::tan(0.5 * double(glm::radians(60.0f))));
    EXPECT_DOUBLE_EQ(camera.cx, 80.0);
    EXPECT_NEAR(glm::length(camera.position - glm::dvec3(3, 2, 4)), 0.0, 1e-5);
    splat_lod::SplatCloud cloud;
    for (const glm::vec3 p : {glm::vec3(0.0f), glm::vec3(0.5f, -0.3f, 0.2f), glm::vec3(-1.0f, 0.4f, 1.0f)})
        add_gaussian(cloud, p, -3.0f, 0.5, {0.5, 0.5, 0.5});
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto g = ref::project_gaussian(cloud, i, glm::dmat4(1.0), camera, {});
        const glm::vec3 expected = view.project_to_pixel(cloud.positions[i]);
        EXPECT_NEAR(g.mean.x, expected.x, 1e-3);
        EXPECT_NEAR(g.mean.y, expected.y, 1e-3);
        EXPECT_NEAR(g.depth, expected.z, 1e-5);
    }
}

TEST(ReferenceRenderer, ProjectedCovarianceMatchesANumericalJacobian) {
    const auto view =
        engine::make_look_at_camera({3, 2, 4}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), 160, 120, 0.1f, 100.0f);
    const auto camera = ref::make_reference_camera(view);
    const glm::dmat4 camera_to_world = glm::inverse(camera.view);
    const auto pixel = [&](const glm::dvec3& v) {  // view space → image, as camera.h states it
        return glm::dvec2(camera.cx + camera.fx * v.x / -v.z, camera.cy - camera.fy * v.y / -v.z);
    };
    splat_lod::SplatCloud cloud;
    const double off_axis = 1.35 * camera.tan_half_fov_x() * 5.0;  // beyond the 1.3·tan(fov/2) clamp
    for (const glm::dvec3 v :
         {glm::dvec3(0.3, -0.2, -5.0), glm::dvec3(-1.0, 0.9, -4.0), glm::dvec3(off_axis, -0.2, -5.0)}) {
        const std::size_t i =
            add_gaussian(cloud, glm::vec3(camera_to_world * glm::dvec4(v, 1.0)), 0.0f, 0.9, {0.5, 0.5, 0.5});
        cloud.log_scales[i] = {-0.5f, -2.0f, -1.0f};
        cloud.rotations[i] = {0.8f, 0.2f, -0.5f, 0.26f};
    }
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto& q = cloud.rotations[i];
        const glm::dmat3 r = glm::mat3_cast(glm::normalize(glm::dquat(q.w, q.x, q.y, q.z)));
        glm::dmat3 scale(0.0);
        for (int k = 0; k < 3; ++k) scale[k][k] = std::exp(double(cloud.log_scales[i][k]));
        const glm::dmat3 w3(camera.view);
        const glm::dmat3 sigma_view = w3 * r * scale * scale * glm::transpose(r) * glm::transpose(w3);
        glm::dvec3 v(camera.view * glm::dvec4(glm::dvec3(cloud.positions[i]), 1.0));
        const double lim = 1.3 * camera.tan_half_fov_x(), z = -v.z;
        v.x = std::clamp(v.x / z, -lim, lim) * z;  // 3DGS evaluates J at the clamped point
        glm::dmat3x2 jacobian;
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 h(0.0);
            h[k] = 1e-5 * z;
            jacobian[k] = (pixel(v + h) - pixel(v - h)) / (2.0 * h[k]);
        }
        const glm::dmat2 expected = jacobian * sigma_view * glm::transpose(jacobian);
        const auto g = ref::project_gaussian(cloud, i, glm::dmat4(1.0), camera, {});
        EXPECT_TRUE(g.drawn()) << ref::to_string(g.cull);
        EXPECT_NEAR(g.cov2d.x, expected[0][0] + 0.3, 1e-6 * expected[0][0]) << i;
        EXPECT_NEAR(g.cov2d.y, expected[1][0], 1e-6 * expected[0][0]) << i;
        EXPECT_NEAR(g.cov2d.z, expected[1][1] + 0.3, 1e-6 * expected[1][1]) << i;
    }
}

TEST(ReferenceRenderer, DisplacementAlongCameraUpRendersHigher) {
    const auto view =
        engine::make_look_at_camera({3, 2, 4}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), 80, 60, 0.1f, 100.0f);
    const glm::dmat4 camera_to_world = glm::inverse(glm::dmat4(view.view));
    const glm::vec3 up(camera_to_world[1]), right(camera_to_world[0]);
    const auto peak = [&](const glm::vec3& p) {
        splat_lod::SplatCloud cloud;
        add_gaussian(cloud, p, -3.0f, 0.9, {1.0, 1.0, 1.0});
        const std::vector<ref::ReferenceInstance> instances{{&cloud, glm::dmat4(1.0)}};
        const auto image = ref::render_reference(instances, view, {});
        glm::ivec2 best(0);
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
                if (image.alpha_at(x, y) > image.alpha_at(best.x, best.y)) best = {x, y};
        return best;
    };
    const glm::ivec2 centre = peak(glm::vec3(0.0f)), above = peak(0.5f * up), beside = peak(0.5f * right);
    EXPECT_LT(above.y, centre.y - 3);
    EXPECT_NEAR(above.x, centre.x, 1);
    EXPECT_GT(beside.x, centre.x + 3);
    EXPECT_NEAR(beside.y, centre.y, 1);
}

TEST(ReferenceRenderer, ShDegreeOneFollowsTheViewDirection) {
    splat_lod::SplatCloud cloud;
    cloud.set_sh_degree(1);
    add_gaussian(cloud, {0.2f, -0.1f, 0.3f}, -3.0f, 0.9, {0.5, 0.5, 0.5});
    const float rest[3][3] = {
        {0.4f, -0.2f, 0.1f}, {-0.3f, 0.5f, 0.2f}, {0.25f, 0.1f, -0.6f}};  // [coefficient][channel]
    for (int k = 1; k <= 3; ++k)
        for (int c = 0; c < 3; ++c) cloud.sh_rest_at(0, k, c) = rest[k - 1][c];
    const auto expected = [&](const glm::dvec3& direction) {
        const glm::dvec3 d = glm::normalize(direction);
        glm::dvec3 colour = 0.5 + kC0 * glm::dvec3(cloud.sh_dc[0]);
        for (int c = 0; c < 3; ++c)
            colour[c] += -kC1 * d.y * rest[0][c] + kC1 * d.z * rest[1][c] - kC1 * d.x * rest[2][c];
        return glm::max(colour, glm::dvec3(0.0));
    };
    const glm::dmat4 model = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 0.0, -1.0)) *
                             glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(0.3, 1.0, 0.2));
    const glm::dvec3 mean = glm::dvec3(model * glm::dvec4(glm::dvec3(cloud.positions[0]), 1.0));
    glm::dvec3 previous(-1.0);
    for (const glm::vec3 eye : {glm::vec3(0, 0, 5), glm::vec3(4, 1, 2), glm::vec3(-3, 3, -4)}) {
        const auto view = engine::make_look_at_camera(eye, glm::vec3(mean), {0, 1, 0}, 1.0f, 32, 32, 0.1f, 100.0f);
        const auto camera = ref::make_reference_camera(view);
        // World direction camera → mean, taken into the cloud's frame by the inverse model rotation.
        const glm::dvec3 local = glm::transpose(glm::dmat3(model)) * (mean - camera.position);
        const auto g = ref::project_gaussian(cloud, 0, model, camera, {});
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.colour[c], expected(local)[c], 1e-9);
        EXPECT_GT(glm::length(g.colour - previous), 0.05);  // the colour does change with the view
        previous = g.colour;
        const auto dc_only = ref::project_gaussian(cloud, 0, model, camera, {}, 0);
        EXPECT_NEAR(glm::length(dc_only.colour - dc_colour(cloud.sh_dc[0])), 0.0, 1e-12);
    }
}

TEST(ReferenceRenderer, ShBasisUpToDegreeThreeIsOrthonormal) {
    // Y_k(d) read back through sh_colour: one Gaussian per basis function, a DC large enough that
    // the clamp at 0 never acts. Orthonormality over the sphere checks the 3DGS constants.
    splat_lod::SplatCloud cloud;
    cloud.set_sh_degree(3);
    cloud.resize(16);
    for (int k = 1; k < 16; ++k) cloud.sh_rest_at(std::size_t(k), k, 0) = 1.0f;
    for (auto& dc : cloud.sh_dc) dc = glm::vec3(20.0f);
    const double offset = 0.5 + 20.0 * kC0;
    std::vector<double> gram(16 * 16, 0.0);
    const int rings = 400, sectors = 32;  // midpoint in cos θ, exact trapezoid in φ
    const double area = (2.0 / rings) * (2.0 * M_PI / sectors);
    for (int a = 0; a < rings; ++a)
        for (int b = 0; b < sectors; ++b) {
            const double u = -1.0 + (a + 0.5) * 2.0 / rings, phi = 2.0 * M_PI * b / sectors;
            const glm::dvec3 d(std::sqrt(1 - u * u) * std::cos(phi), std::sqrt(1 - u * u) * std::sin(phi), u);
            double y[16];
            for (std::size_t k = 0; k < 16; ++k) y[k] = k == 0 ? kC0 : ref::sh_colour(cloud, k, 3, d).x - offset;
            for (int i = 0; i < 16; ++i)
                for (int j = 0; j < 16; ++j) gram[std::size_t(i * 16 + j)] += y[i] * y[j] * area;
        }
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j)
            EXPECT_NEAR(gram[std::size_t(i * 16 + j)], i == j ? 1.0 : 0.0, 1e-3) << i << "," << j;
}

TEST(ReferenceRenderer, NonUniformModelScaleUsesTheLocalViewDirection) {
    splat_lod::SplatCloud cloud;
    cloud.set_sh_degree(1);
    add_gaussian(cloud, {0.3f, 0.2f, 0.0f}, -3.0f, 0.9, {0.5, 0.5, 0.5});
    cloud.sh_rest_at(0, 3, 0) = 0.8f;  // red varies with the local x of the direction
    const glm::dmat4 model =
        glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, -4)) * glm::scale(glm::dmat4(1.0), glm::dvec3(3.0, 1.0, 0.5));
    const auto camera = axis_camera(64, 64);
    const auto g = ref::project_gaussian(cloud, 0, model, camera, {});
    // Documented choice: d_local = normalise(M⁻¹(μ_world − c)) = normalise(p − model⁻¹·c).
    const glm::dvec3 d =
        glm::normalize(glm::dvec3(cloud.positions[0]) - glm::dvec3(glm::inverse(model) * glm::dvec4(0, 0, 0, 1)));
    EXPECT_NEAR(g.colour.x, 0.5 + kC0 * cloud.sh_dc[0].x - kC1 * d.x * 0.8, 1e-9);
    EXPECT_NEAR(g.mean.x, 32.0 + 100.0 * 3.0 * double(cloud.positions[0].x) / 4.0, 1e-9);  // world x = 3·0.3 at depth 4
}

TEST(ReferenceRenderer, OverlappingGaussiansBlendFrontToBackWhateverTheStorageOrder) {
    const glm::dvec3 red(1, 0, 0), blue(0, 0, 1);
    splat_lod::SplatCloud front_first, back_first, front_only, back_only;
    add_gaussian(front_first, {0, 0, -4}, -2.0f, 0.6, red);
    add_gaussian(front_first, {0, 0, -6}, -2.0f, 0.7, blue);
    add_gaussian(back_first, {0, 0, -6}, -2.0f, 0.7, blue);
    add_gaussian(back_first, {0, 0, -4}, -2.0f, 0.6, red);
    add_gaussian(front_only, {0, 0, -4}, -2.0f, 0.6, red);
    add_gaussian(back_only, {0, 0, -6}, -2.0f, 0.7, blue);
    const auto camera = axis_camera(33, 33);
    const auto a = render_cloud(front_first, camera), b = render_cloud(back_first, camera);
    EXPECT_EQ(a.rgb, b.rgb);
    EXPECT_EQ(a.alpha, b.alpha);
    const double of = sigmoid(front_first.opacity_logits[0]), ob = sigmoid(front_first.opacity_logits[1]);
    const glm::dvec3 expected =
        dc_colour(front_first.sh_dc[0]) * of + dc_colour(front_first.sh_dc[1]) * ob * (1.0 - of);
    EXPECT_NEAR(glm::length(a.colour_at(16, 16) - expected), 0.0, 1e-12);
    EXPECT_NEAR(a.alpha_at(16, 16), 1.0 - (1.0 - of) * (1.0 - ob), 1e-12);
    EXPECT_EQ(a.contributors_at(16, 16), 2u);
    // Across instances too: depth decides, not the order of the instances.
    const std::vector<ref::ReferenceInstance> instances{{&back_only, glm::dmat4(1.0)}, {&front_only, glm::dmat4(1.0)}};
    const auto c = ref::render_reference(instances, camera, {});
    EXPECT_LT(max_difference(a, c), 1e-15);
}

// The splats' depth (docs/algorithms.md §1, "Depth") in closed form at the centre pixel of two
// Gaussians centred on it at depths 4 and 6 (α there is the opacity): the median is the depth of the
// splat with which A = 1 − T first exceeds ½, the expected depth Σ dᵢαᵢTᵢ / A; a mesh hides what is
// behind it from both.
TEST(ReferenceRenderer, DepthIsWhereOpacityPassesAHalfAndItsWeightedMean) {
    const auto camera = axis_camera(33, 33);
    const auto two = [](double front, double back) {
        splat_lod::SplatCloud cloud;
        add_gaussian(cloud, {0, 0, -6}, -2.0f, back, {0, 0, 1});
        add_gaussian(cloud, {0, 0, -4}, -2.0f, front, {1, 0, 0});
        return cloud;
    };
    const auto at_centre = [](const ref::ReferenceImage& image) {
        const std::size_t p = image.pixel_index(16, 16);
        return std::pair(image.depth_median[p], image.depth_expected[p]);
    };
    const splat_lod::SplatCloud opaque = two(0.6, 0.7), faint = two(0.3, 0.3);
    const double of = sigmoid(opaque.opacity_logits[1]), ob = sigmoid(opaque.opacity_logits[0]);
    const auto [median, expected] = at_centre(render_cloud(opaque, camera));
    EXPECT_EQ(median, 4.0);  // T = 0.4 after the front one
    EXPECT_NEAR(expected, (4.0 * of + 6.0 * ob * (1.0 - of)) / (1.0 - (1.0 - of) * (1.0 - ob)), 1e-12);
    const double f = sigmoid(faint.opacity_logits[1]);
    const auto [faint_median, faint_expected] = at_centre(render_cloud(faint, camera));
    EXPECT_EQ(faint_median, 6.0);  // T = 0.7, then 0.49
    EXPECT_NEAR(faint_expected, (4.0 * f + 6.0 * f * (1.0 - f)) / (1.0 - (1.0 - f) * (1.0 - f)), 1e-12);
    // A mesh at depth 5 hides the back one: A = 0.3 never passes ½, the expected depth is the front's.
    ref::MeshLayer mesh{33, 33, std::vector<double>(33 * 33, 5.0), std::vector<glm::dvec3>(33 * 33, glm::dvec3(0.0))};
    const ref::ReferenceInstance instance{&faint, glm::dmat4(1.0)};
    const auto [hidden_median, hidden_expected] =
        at_centre(ref::render_reference(std::span(&instance, 1), camera, {}, &mesh));
    EXPECT_EQ(hidden_median, std::numeric_limits<double>::infinity());
    EXPECT_NEAR(hidden_expected, 4.0, 1e-12);
    // No splat: neither.
    const auto empty = render_cloud(splat_lod::SplatCloud{}, camera);
    EXPECT_EQ(empty.depth_median[0], std::numeric_limits<double>::infinity());
    EXPECT_EQ(empty.depth_expected[0], std::numeric_limits<double>::infinity());
}

TEST(ReferenceRenderer, ModelMatrixPlacesAndScalesTheCloud) {
    splat_lod::SplatCloud local, world;
    add_gaussian(local, {0.1f, 0.2f, -1.0f}, -2.5f, 0.7, {0.2, 0.8, 0.4});
    add_gaussian(world, {0.2f, 0.4f - 0.5f, -2.0f - 3.0f}, -2.5f + std::log(2.0f), 0.7, {0.2, 0.8, 0.4});
    const glm::dmat4 model =
        glm::translate(glm::dmat4(1.0), glm::dvec3(0, -0.5, -3)) * glm::scale(glm::dmat4(1.0), glm::dvec3(2.0));
    const auto camera = axis_camera(48, 40);
    EXPECT_LT(max_difference(render_cloud(local, camera, {}, nullptr, model), render_cloud(world, camera)), 1e-6);
}

TEST(ReferenceRenderer, MatchesABruteForcePixelLoopAndIgnoresTheThreadCount) {
    const auto cloud = random_cloud(400, 7);
    const auto camera = axis_camera(64, 48, 60.0);
    ref::ReferenceSettings settings;
    settings.background = {0.1, 0.2, 0.3};
    settings.threads = 1;
    ref::ReferenceStats stats;
    const auto one = render_cloud(cloud, camera, settings, &stats);
    EXPECT_TRUE(stats_add_up(stats));
    EXPECT_GT(stats.drawn, 200u);
    EXPECT_GT(stats.culled_outside, 0u);
    const auto slow = brute_force(cloud, camera, settings);
    EXPECT_LT(max_difference(one, slow), 1e-12);
    EXPECT_EQ(one.contributors, slow.contributors);
    for (const int threads : {2, 3, 7}) {
        settings.threads = threads;
        const auto many = render_cloud(cloud, camera, settings);
        EXPECT_EQ(one.rgb, many.rgb);
        EXPECT_EQ(one.alpha, many.alpha);
    }
}

TEST(ReferenceRenderer, CulledOutsideGaussiansReachNoPixel) {
    const auto cloud = random_cloud(400, 11);
    const auto camera = axis_camera(64, 48, 60.0);
    int outside = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto g = ref::project_gaussian(cloud, i, glm::dmat4(1.0), camera, {});
        if (g.cull != ref::CullReason::outside) continue;
        ++outside;
        for (int y = 0; y < camera.height; ++y)
            for (int x = 0; x < camera.width; ++x) ASSERT_LT(alpha_at_pixel(g, x, y), 1.0 / 255.0) << "Gaussian " << i;
    }
    EXPECT_GT(outside, 10);
}

TEST(ReferenceRenderer, ToImage8RoundsAndClamps) {
    ref::ReferenceImage image{2, 1, {-0.1, 0.5, 1.2, 0.25, 1.0, 0.0}, {0.0, 1.0}, {0, 1}};
    const engine::Image out = ref::to_image8(image);
    ASSERT_EQ(out.rgba.size(), 8u);
    EXPECT_EQ(std::vector<std::uint8_t>(out.rgba.begin(), out.rgba.end()),
              (std::vector<std::uint8_t>{0, 128, 255, 255, 64, 255, 0, 255}));
}

TEST(ReferenceRenderer, RendersARealCaptureWithoutBadPixels) {
    ENGINE_REQUIRE_DATA("splats/playcanvas-engine/biker.compressed.ply");
    const auto path = engine::test::data_file("splats/playcanvas-engine/biker.compressed.ply");
    const splat_lod::SplatCloud cloud = splat_lod::load_splat_file(path);
    // The capture is Y-down: view it with up = (0, −1, 0).
    const auto view = engine::make_look_at_camera({0, -1.6f, -4.5f}, {0, -1.6f, 0}, {0, -1, 0}, glm::radians(50.0f), 96,
                                                  72, 0.1f, 100.0f);
    ref::ReferenceStats stats;
    const std::vector<ref::ReferenceInstance> instances{{&cloud, glm::dmat4(1.0)}};
    const auto image = ref::render_reference(instances, view, {}, nullptr, &stats);
    EXPECT_TRUE(all_finite(image));
    EXPECT_TRUE(stats_add_up(stats));
    EXPECT_EQ(stats.considered, cloud.size());
    EXPECT_GT(stats.drawn, cloud.size() / 4);
    engine::write_png(engine::test::output_dir("splat_reference") / "biker_96x72.png", ref::to_image8(image));
}
