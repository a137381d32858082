// The analytic image derivatives of the CPU reference renderer (docs/algorithms.md §5) against finite
// differences of the renderer itself, and the low-resolution camera of scaled_camera() against the
// native one.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/upscale.h"
#include "splat_reference_test_helpers.h"

namespace ref = splat_lod::reference;
using namespace splat_lod::reference::test;

namespace {

ref::ReferenceSettings gradient_settings() {
    ref::ReferenceSettings settings;
    settings.gradients = true;
    return settings;
}

// A few large, anisotropic, rotated, semi-transparent Gaussians over a 24×20 image: every one
// covers every pixel with α well above 1/255 (no cut edge inside the image), opacities ≤ 0.9 keep
// α under the 0.99 cap, and four of them leave T ≥ 0.5·0.3·0.2·0.4 ≫ 1e−4. The image is then a
// smooth function of the pixel position, which finite differences can check.
splat_lod::SplatCloud smooth_scene() {
    splat_lod::SplatCloud cloud;
    struct Spec {
        glm::vec3 position;
        glm::vec3 log_scale;
        splat_lod::Rotation rotation;
        double opacity;
        glm::dvec3 colour;
    };
    const Spec specs[] = {
        {{0.10f, -0.05f, -5.0f}, {0.55f, 0.20f, -0.3f}, {0.9f, 0.1f, 0.2f, 0.35f}, 0.5, {0.9, 0.3, 0.1}},
        {{-0.20f, 0.15f, -6.0f}, {0.30f, 0.65f, 0.1f}, {0.7f, -0.3f, 0.1f, 0.6f}, 0.7, {0.2, 0.8, 0.4}},
        {{0.25f, 0.10f, -4.5f}, {0.45f, 0.35f, 0.2f}, {0.6f, 0.5f, -0.4f, -0.2f}, 0.8, {0.1, 0.2, 0.95}},
        {{-0.05f, -0.20f, -7.0f}, {0.80f, 0.60f, 0.5f}, {1.0f, 0.0f, 0.0f, 0.0f}, 0.6, {0.6, 0.6, 0.2}},
    };
    for (const Spec& s : specs) {
        const std::size_t i = add_gaussian(cloud, s.position, 0.0f, s.opacity, s.colour);
        cloud.log_scales[i] = s.log_scale;
        cloud.rotations[i] = s.rotation;
    }
    return cloud;
}

ref::ReferenceCamera shifted(ref::ReferenceCamera camera, double dx, double dy) {
    camera.cx += dx;
    camera.cy += dy;
    return camera;
}

// Every pixel blended every Gaussian of the scene: no α = 1/255 cut and no early stop anywhere.
::testing::AssertionResult every_pixel_blends(const ref::ReferenceImage& image, std::uint32_t count) {
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (image.contributors_at(x, y) != count)
                return ::testing::AssertionFailure()
                       << "pixel (" << x << ", " << y << ") blended " << image.contributors_at(x, y) << " splats";
    return ::testing::AssertionSuccess();
}

double max_abs(const std::vector<double>& values) {
    double m = 0.0;
    for (const double v : values) m = std::max(m, std::abs(v));
    return m;
}

}  // namespace

TEST(ReferenceGradients, OffByDefaultAndSplatChannelsAreEmpty) {
    const auto cloud = smooth_scene();
    const auto image = render_cloud(cloud, axis_camera(24, 20, 40.0));
    EXPECT_TRUE(image.splat.empty());
    EXPECT_TRUE(image.splat_dx.empty() && image.splat_dy.empty() && image.splat_dxy.empty());
    EXPECT_THROW(ref::to_gradient_image(image), engine::Error);
}

// Image coordinates x right, y down: shifting the principal point by h shifts the image,
// I(x; cx + h) = I(x − h; cx), so ∂I/∂x = −∂I/∂cx and ∂²I/∂x∂y = ∂²I/∂cx∂cy. Central differences
// with h = 1e−3 px: the truncation error is about h²/6·|I'''| ≈ 2e−7·|I'''| (|I'''| ≲ 1e−3/px³ for
// these blobs) and the rounding error about ε·|I|/h ≈ 1e−13 for the first and ε·|I|/h² ≈ 1e−10 for
// the mixed derivative; measured max 1.2e−10 for all three. The tolerance 1e−8 + 1e−5·max|analytic|
// (≈ 3.7e−7 for ∂x, ∂y and 2.7e−8 for ∂xy here) keeps two orders of margin over that, and a wrong or
// missing term, of the size of the derivative itself (~1e−3), fails it by four.
TEST(ReferenceGradients, AnalyticDerivativesMatchFiniteDifferences) {
    const auto cloud = smooth_scene();
    const auto camera = axis_camera(24, 20, 40.0);
    const auto settings = gradient_settings();
    const double h = 1e-3;
    const auto image = render_cloud(cloud, camera, settings);
    ASSERT_TRUE(every_pixel_blends(image, static_cast<std::uint32_t>(cloud.size())));
    const auto minus_x = render_cloud(cloud, shifted(camera, -h, 0.0), settings);
    const auto plus_x = render_cloud(cloud, shifted(camera, h, 0.0), settings);
    const auto minus_y = render_cloud(cloud, shifted(camera, 0.0, -h), settings);
    const auto plus_y = render_cloud(cloud, shifted(camera, 0.0, h), settings);
    const auto pp = render_cloud(cloud, shifted(camera, h, h), settings);
    const auto pm = render_cloud(cloud, shifted(camera, h, -h), settings);
    const auto mp = render_cloud(cloud, shifted(camera, -h, h), settings);
    const auto mm = render_cloud(cloud, shifted(camera, -h, -h), settings);
    for (const auto* shifted_image : {&minus_x, &plus_x, &minus_y, &plus_y, &pp, &pm, &mp, &mm})
        ASSERT_TRUE(every_pixel_blends(*shifted_image, static_cast<std::uint32_t>(cloud.size())));

    const double tol_x = 1e-8 + 1e-5 * max_abs(image.splat_dx);
    const double tol_y = 1e-8 + 1e-5 * max_abs(image.splat_dy);
    const double tol_xy = 1e-8 + 1e-5 * max_abs(image.splat_dxy);
    ASSERT_GT(max_abs(image.splat_dx), 1e-3);  // the scene is not flat: the check has teeth
    ASSERT_GT(max_abs(image.splat_dxy), 1e-4);
    double worst_x = 0.0, worst_y = 0.0, worst_xy = 0.0;
    for (std::size_t i = 0; i < image.splat.size(); ++i) {
        const double fd_x = (minus_x.splat[i] - plus_x.splat[i]) / (2.0 * h);
        const double fd_y = (minus_y.splat[i] - plus_y.splat[i]) / (2.0 * h);
        const double fd_xy = (pp.splat[i] - pm.splat[i] - mp.splat[i] + mm.splat[i]) / (4.0 * h * h);
        EXPECT_NEAR(image.splat_dx[i], fd_x, tol_x) << "pixel " << i / 4 << " channel " << i % 4;
        EXPECT_NEAR(image.splat_dy[i], fd_y, tol_y) << "pixel " << i / 4 << " channel " << i % 4;
        EXPECT_NEAR(image.splat_dxy[i], fd_xy, tol_xy) << "pixel " << i / 4 << " channel " << i % 4;
        worst_x = std::max(worst_x, std::abs(image.splat_dx[i] - fd_x));
        worst_y = std::max(worst_y, std::abs(image.splat_dy[i] - fd_y));
        worst_xy = std::max(worst_xy, std::abs(image.splat_dxy[i] - fd_xy));
    }
    std::printf("[ measured ] max |analytic - FD|: dx %.3g of %.3g, dy %.3g of %.3g, dxy %.3g of %.3g\n", worst_x,
                max_abs(image.splat_dx), worst_y, max_abs(image.splat_dy), worst_xy, max_abs(image.splat_dxy));
}

// One Gaussian: C = c·α, A = α, so ∂C/∂x = c·α·g_x and ∂²C/∂x∂y = c·α·(g_x g_y + g_xy) in closed
// form. Also checks the splat layer excludes the background while rgb includes it.
TEST(ReferenceGradients, SingleGaussianHasClosedFormDerivatives) {
    splat_lod::SplatCloud cloud;
    const std::size_t i = add_gaussian(cloud, {0.1f, -0.05f, -5.0f}, 0.0f, 0.8, {0.9, 0.5, 0.2});
    cloud.log_scales[i] = {-2.5f, -3.0f, -2.8f};
    cloud.rotations[i] = {0.9f, 0.0f, 0.0f, 0.4f};  // about the view axis: a tilted ellipse, Cxy ≠ 0
    const auto camera = axis_camera(32, 32, 100.0);
    auto settings = gradient_settings();
    settings.background = {0.25, 0.5, 0.75};
    const auto image = render_cloud(cloud, camera, settings);
    const auto g = ref::project_gaussian(cloud, 0, glm::dmat4(1.0), camera, settings);
    ASSERT_TRUE(g.drawn());
    ASSERT_GT(std::abs(g.conic.y), 1e-3);
    int checked = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const double alpha = alpha_at_pixel(g, x, y);
            const std::size_t p = 4 * image.pixel_index(x, y);
            if (alpha < ref::kMinAlpha) {
                for (int c = 0; c < 4; ++c) EXPECT_EQ(image.splat_dx[p + static_cast<std::size_t>(c)], 0.0);
                continue;
            }
            const glm::dvec2 d = glm::dvec2(x + 0.5, y + 0.5) - g.mean;
            const double g_x = -(g.conic.x * d.x + g.conic.y * d.y), g_y = -(g.conic.y * d.x + g.conic.z * d.y);
            const glm::dvec4 value(g.colour * alpha, alpha);
            const glm::dvec4 colour(g.colour, 1.0);
            for (int c = 0; c < 4; ++c) {
                const std::size_t k = p + static_cast<std::size_t>(c);
                EXPECT_NEAR(image.splat[k], value[c], 1e-14);
                EXPECT_NEAR(image.splat_dx[k], colour[c] * alpha * g_x, 1e-12);
                EXPECT_NEAR(image.splat_dy[k], colour[c] * alpha * g_y, 1e-12);
                EXPECT_NEAR(image.splat_dxy[k], colour[c] * alpha * (g_x * g_y - g.conic.y), 1e-12);
            }
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(image.rgb[3 * image.pixel_index(x, y) + static_cast<std::size_t>(c)],
                            value[c] + (1.0 - alpha) * settings.background[c], 1e-14);
            ++checked;
        }
    EXPECT_GT(checked, 20);
}

// The derivative path must not change what the colour path computes, bit for bit.
TEST(ReferenceGradients, ColourOutputIsUnchangedWhenGradientsAreOn) {
    const auto cloud = smooth_scene();
    const auto camera = axis_camera(40, 30, 60.0);
    const auto plain = render_cloud(cloud, camera);
    const auto with = render_cloud(cloud, camera, gradient_settings());
    EXPECT_EQ(plain.rgb, with.rgb);
    EXPECT_EQ(plain.alpha, with.alpha);
    EXPECT_EQ(plain.contributors, with.contributors);
    for (std::size_t p = 0; p < plain.alpha.size(); ++p) {
        EXPECT_EQ(with.splat[4 * p + 3], plain.alpha[p]);
        for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(with.splat[4 * p + c], plain.rgb[3 * p + c]);  // background 0
    }
}

// A mesh surface between the Gaussians cuts the derivatives exactly like the colour: the layer
// equals the render of the splats in front of it alone, and the mesh colour is not in it.
TEST(ReferenceGradients, MeshDepthCutsTheDerivativesLikeTheColour) {
    const auto cloud = smooth_scene();  // depths 4.5, 5, 6, 7
    const auto camera = axis_camera(24, 20, 40.0);
    ref::MeshLayer mesh;
    mesh.width = camera.width;
    mesh.height = camera.height;
    mesh.depth.assign(static_cast<std::size_t>(camera.width * camera.height), 5.5);
    mesh.colour.assign(mesh.depth.size(), glm::dvec3(0.3, 0.6, 0.9));
    const ref::ReferenceInstance instance{&cloud, glm::dmat4(1.0)};
    const auto cut = ref::render_reference(std::span(&instance, 1), camera, gradient_settings(), &mesh);

    splat_lod::SplatCloud front;
    for (const std::size_t i : {0u, 2u}) {
        const std::size_t j = add_gaussian(front, cloud.positions[i], 0.0f, 0.5, {0.5, 0.5, 0.5});
        front.log_scales[j] = cloud.log_scales[i];
        front.rotations[j] = cloud.rotations[i];
        front.opacity_logits[j] = cloud.opacity_logits[i];
        front.sh_dc[j] = cloud.sh_dc[i];
    }
    const auto expected = render_cloud(front, camera, gradient_settings());
    for (std::size_t k = 0; k < cut.splat.size(); ++k) {
        EXPECT_NEAR(cut.splat[k], expected.splat[k], 1e-14);
        EXPECT_NEAR(cut.splat_dx[k], expected.splat_dx[k], 1e-14);
        EXPECT_NEAR(cut.splat_dy[k], expected.splat_dy[k], 1e-14);
        EXPECT_NEAR(cut.splat_dxy[k], expected.splat_dxy[k], 1e-14);
    }
    EXPECT_GT(max_abs(cut.splat_dx), 1e-3);
}

TEST(ReferenceGradients, PixelsWithoutSplatsHaveZeroDerivatives) {
    splat_lod::SplatCloud cloud;
    add_gaussian(cloud, {0.0f, 0.0f, -5.0f}, std::log(0.02f), 0.9, {1.0, 1.0, 1.0});  // a few pixels wide
    const auto image = render_cloud(cloud, axis_camera(32, 32, 100.0), gradient_settings());
    int empty = 0;
    for (std::size_t p = 0; p < image.contributors.size(); ++p) {
        if (image.contributors[p] != 0) continue;
        ++empty;
        for (std::size_t c = 0; c < 4; ++c) {
            EXPECT_EQ(image.splat[4 * p + c], 0.0);
            EXPECT_EQ(image.splat_dx[4 * p + c], 0.0);
            EXPECT_EQ(image.splat_dy[4 * p + c], 0.0);
            EXPECT_EQ(image.splat_dxy[4 * p + c], 0.0);
        }
    }
    EXPECT_GT(empty, 500);
}

TEST(ReferenceGradients, ToGradientImageConvertsEveryPlane) {
    const auto cloud = smooth_scene();
    const auto image = render_cloud(cloud, axis_camera(12, 10, 20.0), gradient_settings());
    const auto low = ref::to_gradient_image(image);
    ASSERT_EQ(low.width, 12);
    ASSERT_EQ(low.height, 10);
    ASSERT_EQ(low.value.size(), image.splat.size());
    for (std::size_t k = 0; k < image.splat.size(); ++k) {
        EXPECT_EQ(low.value[k], static_cast<float>(image.splat[k]));
        EXPECT_EQ(low.dx[k], static_cast<float>(image.splat_dx[k]));
        EXPECT_EQ(low.dy[k], static_cast<float>(image.splat_dy[k]));
        EXPECT_EQ(low.dxy[k], static_cast<float>(image.splat_dxy[k]));
    }
    EXPECT_EQ(low.texel(3, 2), 4u * (2u * 12u + 3u));
}

// The low-resolution camera maps a mean at native μ (pixel-corner origin) to s·μ, i.e. in texel-
// centre coordinates (μ − ½) to (μ − ½ + ½)·s − ½, the mapping of upscale.h.
TEST(ScaledCamera, MapsProjectedMeansLikeTheUpscaler) {
    splat_lod::SplatCloud cloud;
    for (const glm::vec3 p :
         {glm::vec3(0.0f, 0.0f, -5.0f), glm::vec3(0.7f, -0.4f, -4.0f), glm::vec3(-1.1f, 0.9f, -6.0f)})
        add_gaussian(cloud, p, -2.0f, 0.8, {0.5, 0.5, 0.5});
    auto full = axis_camera(37, 23, 30.0);
    full.cx = 18.2;  // off-centre, so the scale acts on cx too
    for (const double s : {1.0, 1.0 / 1.5, 1.0 / 3.0, 1.0 / 3.7}) {
        const auto low = ref::scaled_camera(full, s);
        EXPECT_EQ(low.width, splat_lod::upscale::low_res_size(37, s));
        EXPECT_EQ(low.height, splat_lod::upscale::low_res_size(23, s));
        EXPECT_DOUBLE_EQ(low.clamp_tan_x, full.tan_half_fov_x());
        EXPECT_DOUBLE_EQ(low.clamp_tan_y, full.tan_half_fov_y());
        for (std::size_t i = 0; i < cloud.size(); ++i) {
            const auto native = ref::project_gaussian(cloud, i, glm::dmat4(1.0), full, {});
            const auto scaled = ref::project_gaussian(cloud, i, glm::dmat4(1.0), low, {});
            const glm::dvec2 native_texel = native.mean - 0.5, scaled_texel = scaled.mean - 0.5;
            EXPECT_NEAR(scaled_texel.x, (native_texel.x + 0.5) * s - 0.5, 1e-12) << "s " << s << " gaussian " << i;
            EXPECT_NEAR(scaled_texel.y, (native_texel.y + 0.5) * s - 0.5, 1e-12) << "s " << s << " gaussian " << i;
        }
    }
    EXPECT_EQ(ref::scaled_camera(full, 1.0 / 3.0).width, 13);  // ceil(37/3): one texel past the output
}

// With the dilation scaled by s² (docs/algorithms.md §5), the low-resolution image is the native one
// sampled at the native pixel centres that coincide with texel centres (x = 3k + 1 at s = 1/3),
// and its derivatives are the native ones × 1/s (× 1/s² for ∂xy). A Gaussian beyond the ±1.3·tan
// Jacobian clamp makes this depend on clamp_tan_x: without it the rounded-up low-resolution image
// (13 texels for 37 px) would clamp at a different angle.
TEST(ScaledCamera, LowResolutionRenderSamplesTheNativeImage) {
    auto full = axis_camera(37, 24, 30.0);
    splat_lod::SplatCloud cloud;
    const float beyond_clamp = static_cast<float>(1.45 * full.tan_half_fov_x() * 5.0);
    add_gaussian(cloud, {beyond_clamp, 0.2f, -5.0f}, std::log(1.2f), 0.7, {0.9, 0.4, 0.1});
    add_gaussian(cloud, {0.3f, -0.2f, -4.0f}, std::log(0.15f), 0.8, {0.1, 0.5, 0.9});
    const double s = 1.0 / 3.0;
    auto native_settings = gradient_settings();
    auto low_settings = gradient_settings();
    low_settings.dilation = native_settings.dilation * s * s;
    const auto native = render_cloud(cloud, full, native_settings);
    const auto low_camera = ref::scaled_camera(full, s);
    const auto low = render_cloud(cloud, low_camera, low_settings);
    ASSERT_EQ(low.width, 13);
    ASSERT_EQ(low.height, 8);

    double worst = 0.0;
    for (int ty = 0; ty < low.height; ++ty)
        for (int tx = 0; tx < low.width; ++tx) {
            const int x = 3 * tx + 1, y = 3 * ty + 1;
            if (x >= full.width || y >= full.height) continue;  // the extra texel column
            const std::size_t lp = 4 * low.pixel_index(tx, ty), np = 4 * native.pixel_index(x, y);
            for (std::size_t c = 0; c < 4; ++c) {
                EXPECT_NEAR(low.splat[lp + c], native.splat[np + c], 1e-12);
                EXPECT_NEAR(low.splat_dx[lp + c], 3.0 * native.splat_dx[np + c], 1e-11);
                EXPECT_NEAR(low.splat_dy[lp + c], 3.0 * native.splat_dy[np + c], 1e-11);
                EXPECT_NEAR(low.splat_dxy[lp + c], 9.0 * native.splat_dxy[np + c], 1e-10);
                worst = std::max(worst, std::abs(low.splat[lp + c] - native.splat[np + c]));
            }
        }
    EXPECT_LT(worst, 1e-12);

    // Without the clamp override the clamped Gaussian comes out differently: the override matters.
    auto unclamped_camera = low_camera;
    unclamped_camera.clamp_tan_x = unclamped_camera.clamp_tan_y = 0.0;
    const auto differs = render_cloud(cloud, unclamped_camera, low_settings);
    double change = 0.0;
    for (std::size_t k = 0; k < low.splat.size(); ++k)
        change = std::max(change, std::abs(differs.splat[k] - low.splat[k]));
    EXPECT_GT(change, 1e-4);
}

TEST(ScaledCamera, RejectsScalesOutsideZeroToOne) {
    const auto full = axis_camera(32, 24);
    for (const double s :
         {0.0, -0.5, 1.0001, 2.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
        EXPECT_THROW(ref::scaled_camera(full, s), engine::Error) << s;
    EXPECT_NO_THROW(ref::scaled_camera(full, 1.0));
    EXPECT_NO_THROW(ref::scaled_camera(full, 1e-3));
    auto bad = full;
    bad.clamp_tan_x = -1.0;
    EXPECT_THROW(render_cloud(splat_lod::SplatCloud{}, bad), engine::Error);
}
