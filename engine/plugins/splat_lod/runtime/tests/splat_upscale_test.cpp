// Gradient-aware upscaling on the GPU (docs/algorithms.md §5): the low-resolution raster's analytic
// derivatives against the CPU reference, the upscale pass against the CPU upscalers, compositing
// with meshes, LOD selection at the output's coverage, and the hard cases.
#include <cmath>
#include <limits>

#include "engine/core/error.h"
#include "engine/render/render_target.h"
#include "engine/render/scene_camera.h"
#include "engine/scene/scene_loader.h"
#include "gpu_fixture.h"
#include "splat_lod/core/lod_selection.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/upscale.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace ref = splat_lod::reference;
namespace up = splat_lod::upscale;
using engine::test::GaussianSpec;
using plugin_msgs::Upscaler;

namespace {

constexpr Upscaler kUpscalers[] = {Upscaler::spline, Upscaler::bicubic, Upscaler::bilinear, Upscaler::lanczos3};

std::shared_ptr<const splat_lod::SplatCloud> shared(splat_lod::SplatCloud cloud) {
    return std::make_shared<const splat_lod::SplatCloud>(std::move(cloud));
}

// Smooth content: a few dozen semi-transparent Gaussians of 1–6 output px, some overlapping.
splat_lod::SplatCloud smooth_cloud(int count, float log_scale_base) {
    std::vector<GaussianSpec> specs;
    for (int i = 0; i < count; ++i) {
        const float t = static_cast<float>(i);
        specs.push_back({{0.9f * std::sin(t * 1.7f), 0.7f * std::cos(t * 2.3f), 0.5f * std::sin(t * 0.37f)},
                         {log_scale_base + 0.6f * std::sin(t), log_scale_base + 0.5f * std::cos(t * 1.3f), -2.5f},
                         glm::normalize(glm::vec4(1.0f, std::sin(t), std::cos(t * 0.7f), 0.3f)),
                         0.5f + std::sin(t * 0.91f),
                         {0.5f + 0.4f * std::sin(t), 0.5f + 0.4f * std::cos(t), 0.7f}});
    }
    return engine::test::make_cloud(specs);
}

engine::CameraView front_camera(int width, int height) {
    return engine::make_look_at_camera({0.0f, 0.0f, 4.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, glm::radians(40.0f),
                                       width, height, 0.01f, 100.0f);
}

class SplatUpscaleTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness harness;

    splat_lod::SplatRenderer pass() { return splat_lod::SplatRenderer(harness.engine().renderer()); }

    engine::Image render(const std::shared_ptr<const splat_lod::SplatCloud>& cloud, const engine::CameraView& camera,
                         float render_scale, Upscaler upscaler = Upscaler::spline,
                         const glm::vec3& background = glm::vec3(0.0f)) {
        harness.edit_lod([&](plugin_msgs::LodSettings& lod) {
            lod.render_scale = render_scale;
            lod.upscaler = upscaler;
        });
        return harness.render({cloud}, camera, background);
    }

    // The CPU upscaler applied to the GPU's own low-resolution image, composited over a uniform
    // background as the upscale pass composites over the mesh layer.
    engine::Image cpu_upscale(const up::GradientImage& low, int width, int height, double render_scale,
                              Upscaler upscaler, const glm::vec3& background = glm::vec3(0.0f)) {
        const up::Rgba32f out = up::upscale_image(low, width, height, render_scale, upscaler);
        engine::Image image;
        image.width = width;
        image.height = height;
        image.rgba.resize(std::size_t(width) * std::size_t(height) * 4);
        for (std::size_t p = 0; p < std::size_t(width) * std::size_t(height); ++p) {
            const float* v = &out.rgba[4 * p];
            for (int c = 0; c < 3; ++c) {
                const double value = std::clamp(double(v[c]) + (1.0 - double(v[3])) * double(background[c]), 0.0, 1.0);
                image.rgba[4 * p + std::size_t(c)] = static_cast<std::uint8_t>(std::lround(value * 255.0));
            }
            image.rgba[4 * p + 3] = 255;
        }
        return image;
    }
};

// The largest 8-bit difference of any channel between two images of one size.
int max_difference(const engine::Image& a, const engine::Image& b) {
    int worst = 0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) worst = std::max(worst, std::abs(int(a.rgba[i]) - int(b.rgba[i])));
    return worst;
}

}  // namespace

// The raster's low-resolution C, A and their ∂x, ∂y, ∂xy (float, GPU) against the reference's
// (double), rendered with the same low-resolution camera and the dilation 0.3·s².
TEST_F(SplatUpscaleTest, LowResolutionDerivativesMatchTheReference) {
    const auto cloud = shared(smooth_cloud(40, -2.6f));
    const int width = 96, height = 72;
    const double s = 1.0 / 3.0;
    const auto camera = front_camera(width, height);
    render(cloud, camera, static_cast<float>(s));
    const up::GradientImage gpu = pass().read_low_res_image();
    ASSERT_EQ(gpu.width, 32);
    ASSERT_EQ(gpu.height, 24);

    ref::ReferenceSettings settings;
    settings.gradients = true;
    settings.dilation = 0.3 * s * s;
    // The reference draws what the GPU scene stores: the compact records, decoded.
    const splat_lod::SplatCloud stored = splat_lod::compact_round_trip(*cloud, cloud->sh_degree);
    const ref::ReferenceInstance instance{&stored, glm::dmat4(1.0), splat_lod::kMaxShDegree};
    const auto low_camera = ref::scaled_camera(ref::make_reference_camera(camera), s);
    const up::GradientImage cpu =
        ref::to_gradient_image(ref::render_reference(std::span(&instance, 1), low_camera, settings));
    ASSERT_EQ(cpu.width, gpu.width);
    ASSERT_EQ(cpu.height, gpu.height);

    // Float against double: values to 2e-4, derivatives to 2e-4 of their largest magnitude.
    const std::vector<float>* gpu_images[] = {&gpu.value, &gpu.dx, &gpu.dy, &gpu.dxy};
    const std::vector<float>* cpu_images[] = {&cpu.value, &cpu.dx, &cpu.dy, &cpu.dxy};
    const char* names[] = {"value", "dx", "dy", "dxy"};
    for (int k = 0; k < 4; ++k) {
        float largest = 0.0f, worst = 0.0f;
        for (const float v : *cpu_images[k]) largest = std::max(largest, std::abs(v));
        for (std::size_t i = 0; i < cpu_images[k]->size(); ++i) {
            ASSERT_TRUE(std::isfinite((*gpu_images[k])[i])) << names[k] << " " << i;
            worst = std::max(worst, std::abs((*gpu_images[k])[i] - (*cpu_images[k])[i]));
        }
        EXPECT_GT(largest, 0.01f) << names[k] << " is all but zero: the test scene is too flat";
        EXPECT_LE(worst, 2e-4f * std::max(1.0f, largest)) << names[k] << " (largest " << largest << ")";
        RecordProperty(std::string(names[k]) + "_max_error", std::to_string(worst));
    }
}

// The upscale pass against the CPU upscalers on the GPU's own low-resolution image, for every
// method, integer and fractional factors and odd sizes: at most one 8-bit step apart.
TEST_F(SplatUpscaleTest, UpscalePassMatchesTheCpuUpscalers) {
    const auto cloud = shared(smooth_cloud(120, -3.4f));
    const glm::vec3 background(0.2f, 0.3f, 0.4f);
    struct Case {
        int width, height;
        double scale;
    };
    for (const Case c : {Case{96, 72, 1.0 / 3.0}, Case{96, 72, 0.5}, Case{37, 23, 1.0 / 3.0}, Case{50, 31, 1.0 / 2.5},
                         Case{45, 45, 1.0 / 1.5}, Case{64, 48, 1.0 / 3.7}}) {
        for (const Upscaler u : kUpscalers) {
            SCOPED_TRACE(std::to_string(c.width) + "x" + std::to_string(c.height) + " s=" + std::to_string(c.scale) +
                         " " + std::string(plugin_msgs::to_string(u)));
            const auto gpu = render(cloud, front_camera(c.width, c.height), static_cast<float>(c.scale), u, background);
            const up::GradientImage low = pass().read_low_res_image();
            ASSERT_EQ(low.width, up::low_res_size(c.width, static_cast<float>(c.scale)));
            ASSERT_EQ(low.height, up::low_res_size(c.height, static_cast<float>(c.scale)));
            const auto cpu = cpu_upscale(low, c.width, c.height, static_cast<float>(c.scale), u, background);
            EXPECT_LE(max_difference(gpu, cpu), 1);
        }
    }
}

// At 3× the spline keeps close to the native render of small, detailed content, and beats the
// bicubic: resolution-consistent dilation plus exact derivatives (docs/algorithms.md §5).
TEST_F(SplatUpscaleTest, SplineAtThreeTimesIsCloseToNativeAndBeatsBicubic) {
    const auto cloud = shared(smooth_cloud(400, -3.6f));
    const auto camera = front_camera(192, 144);
    const auto native = render(cloud, camera, 1.0f);
    double psnr[4] = {};
    for (int k = 0; k < 4; ++k) {
        const auto image = render(cloud, camera, 1.0f / 3.0f, kUpscalers[k]);
        psnr[k] = engine::compare_images(image, native).psnr_db;
        RecordProperty(std::string(plugin_msgs::to_string(kUpscalers[k])) + "_psnr_db", std::to_string(psnr[k]));
    }
    EXPECT_GE(psnr[0], 38.0);
    EXPECT_GE(psnr[0], psnr[1] + 3.0) << "spline " << psnr[0] << " dB, bicubic " << psnr[1] << " dB";
    EXPECT_GT(psnr[1], psnr[2]) << "bicubic should beat bilinear";

    // Without the resolution-consistent dilation the low-resolution image is blurred f² times too
    // much: every upscaler loses.
    pass().settings().scaled_dilation = false;
    const double plain = engine::compare_images(render(cloud, camera, 1.0f / 3.0f), native).psnr_db;
    pass().settings().scaled_dilation = true;
    EXPECT_LT(plain, psnr[0] - 3.0) << "plain dilation " << plain << " dB";
}

// Render scale 1 is the native path exactly, and leaves no low-resolution images behind.
TEST_F(SplatUpscaleTest, RenderScaleOneIsNative) {
    const auto cloud = shared(smooth_cloud(60, -3.0f));
    const auto camera = front_camera(80, 60);
    const auto before = render(cloud, camera, 1.0f);
    render(cloud, camera, 0.5f);
    EXPECT_EQ(pass().read_low_res_image().width, 40);
    const auto after = render(cloud, camera, 1.0f);
    EXPECT_EQ(max_difference(before, after), 0);
    EXPECT_EQ(pass().read_low_res_image().width, 0);
}

// LOD selection uses the coverage at the output resolution: the same Gaussians per level are
// drawn at render scale 1/3 as natively. Coverage ranges sit a factor 3 away from this view's
// coverage (as in splat_pipeline_test), so float rounding at either resolution cannot flip one.
TEST_F(SplatUpscaleTest, LodSelectionUsesTheOutputCoverage) {
    auto cloud = smooth_cloud(400, -3.2f);
    const auto camera = front_camera(160, 120);
    const auto ref_camera = ref::make_reference_camera(camera);
    const ref::ReferenceSettings settings;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto p = ref::project_gaussian(cloud, i, glm::dmat4(1.0), ref_camera, settings);
        const glm::dvec3 c = p.cov2d - glm::dvec3(settings.dilation, 0.0, settings.dilation);
        const double coverage = splat_lod::pixel_coverage(c.x, c.y, c.z, p.opacity);
        cloud.lod_level[i] = static_cast<std::uint8_t>(1 + i % 4);
        const double f = (i % 3 == 0) ? 3.0 : (i % 3 == 1 ? 1.0 / 3.0 : 1.0);
        cloud.coverage_min[i] = (i % 5 == 0) ? -1.0f : static_cast<float>(coverage * f);
        cloud.coverage_max[i] = (i % 7 == 0) ? -1.0f : static_cast<float>(coverage / f);
    }
    const auto scene = shared(cloud);
    harness.edit_lod([](plugin_msgs::LodSettings& lod) { lod.rule.mode = plugin_msgs::LodMode::full; });
    render(scene, camera, 1.0f);
    const auto native = pass().latest_statistics()->per_level;
    render(scene, camera, 1.0f / 3.0f);
    const auto low = pass().latest_statistics()->per_level;
    EXPECT_EQ(native, low);
    std::uint64_t drawn = 0;
    for (const auto n : native) drawn += n;
    EXPECT_GT(drawn, 50u);
    EXPECT_LT(drawn, 350u);  // the rule left some out
}

// Silhouettes (the biker between two boxes): inside the front box the frame is the mesh pass's
// colour exactly, away from the box's edges the splats match native, and the whole frame stays
// within a few dB of native.
TEST_F(SplatUpscaleTest, MeshesHideSplatsWithSharpEdges) {
    auto& engine = harness.engine();
    const auto scene_file = engine::test::repo_dir() / "content/scenes/biker_with_boxes.json";
    const auto full = engine.load_scene(scene_file);
    const int w = 240, h = 180;
    const auto camera = *engine::scene_camera(*full, "", w, h);
    engine::RenderTarget target(w, h);
    auto render_frame = [&](const engine::Scene& scene, float s) {
        harness.edit_lod([&](plugin_msgs::LodSettings& lod) { lod.render_scale = s; });
        splat_lod::render_complete(engine, scene, camera, target);
        return target.read_color();
    };
    const engine::Image native = render_frame(*full, 1.0f);
    const engine::Image upscaled = render_frame(*full, 1.0f / 3.0f);

    auto meshes_only = engine.load_scene(scene_file);
    meshes_only->find_node("biker")->find_component<splat_lod::SplatComponent>()->cloud =
        std::make_shared<const splat_lod::SplatCloud>();
    const engine::Image meshes = render_frame(*meshes_only, 1.0f);
    const std::vector<float> depth = target.read_view_depth();  // the meshes' alone

    // Pixels where native shows the mesh untouched (a mesh nearer than every splat there) and
    // whose 5×5 neighbourhood is the same kind: the upscaled frame must equal the mesh there.
    auto index = [&](int x, int y) { return std::size_t(y) * std::size_t(w) + std::size_t(x); };
    auto same = [&](const engine::Image& a, const engine::Image& b, std::size_t p) {
        return std::equal(&a.rgba[4 * p], &a.rgba[4 * p + 3], &b.rgba[4 * p]);
    };
    int hidden = 0, hidden_wrong = 0;
    for (int y = 2; y < h - 2; ++y)
        for (int x = 2; x < w - 2; ++x) {
            bool interior = std::isfinite(depth[index(x, y)]);
            for (int dy = -2; dy <= 2 && interior; ++dy)
                for (int dx = -2; dx <= 2 && interior; ++dx) {
                    const std::size_t q = index(x + dx, y + dy);
                    interior = same(native, meshes, q) && std::abs(depth[q] - depth[index(x, y)]) < 0.05f;
                }
            if (!interior) continue;
            ++hidden;
            hidden_wrong += same(upscaled, meshes, index(x, y)) ? 0 : 1;
        }
    EXPECT_GT(hidden, 500);
    EXPECT_EQ(hidden_wrong, 0) << "of " << hidden << " mesh pixels";
    const double psnr = engine::compare_images(upscaled, native).psnr_db;
    RecordProperty("composite_psnr_db", std::to_string(psnr));
    const auto out = engine::test::output_dir("splat_upscale");
    engine::write_png(out / "boxes_native.png", native);  // for looking at, pass or fail
    engine::write_png(out / "boxes_spline_3x.png", upscaled);
    EXPECT_GE(psnr, 30.0);
}

// Hard cases: one-pixel Gaussians (huge derivatives), a 1×1 output, a 4096-wide output and
// render scales that leave a partial texel: every value finite, nothing out of range.
TEST_F(SplatUpscaleTest, HardCasesStayFiniteAndInRange) {
    std::vector<GaussianSpec> specs;
    for (int i = 0; i < 200; ++i) {
        const float t = static_cast<float>(i);
        specs.push_back({{std::sin(t * 1.3f), 0.7f * std::cos(t * 2.1f), 0.0f},
                         glm::vec3(-7.0f),
                         {1, 0, 0, 0},
                         6.0f,
                         {0.9f * std::abs(std::sin(t)), 0.9f, 0.2f}});
    }
    const auto needles = shared(engine::test::make_cloud(specs));
    struct Case {
        int width, height;
        float scale;
    };
    for (const Case c : {Case{160, 120, 1.0f / 3.0f}, Case{1, 1, 0.5f}, Case{4096, 4, 1.0f / 3.0f}, Case{33, 17, 0.37f},
                         Case{20, 20, 1.0f / 8.0f}}) {
        for (const Upscaler u : kUpscalers) {
            SCOPED_TRACE(std::to_string(c.width) + "x" + std::to_string(c.height) + " " +
                         std::string(plugin_msgs::to_string(u)));
            const auto image = render(needles, front_camera(c.width, c.height), c.scale, u, {0.1f, 0.1f, 0.1f});
            ASSERT_EQ(image.width, c.width);
            const up::GradientImage low = pass().read_low_res_image();
            for (const auto* channel : {&low.value, &low.dx, &low.dy, &low.dxy})
                for (const float v : *channel) ASSERT_TRUE(std::isfinite(v));
            for (std::size_t i = 3; i < image.rgba.size(); i += 4) ASSERT_EQ(image.rgba[i], 255);
            const auto cpu = cpu_upscale(low, c.width, c.height, c.scale, u, {0.1f, 0.1f, 0.1f});
            EXPECT_LE(max_difference(image, cpu), 1);
        }
    }
    // An impossible render scale is a clear error, not a frame of garbage.
    harness.edit_lod([](plugin_msgs::LodSettings& lod) { lod.render_scale = 0.0f; });
    EXPECT_THROW(harness.render({needles}, front_camera(8, 8)), engine::Error);
    harness.edit_lod([](plugin_msgs::LodSettings& lod) {
        lod.render_scale = 0.5f;
        lod.rule.size_threshold_px = std::numeric_limits<float>::quiet_NaN();  // any field of the rule
    });
    EXPECT_THROW(harness.render({needles}, front_camera(8, 8)), engine::Error);
    harness.edit_lod([](plugin_msgs::LodSettings& lod) { lod.rule = plugin_msgs::LodRule{}; });
    pass().settings().low_res_tile_size = 5;
    EXPECT_THROW(harness.render({needles}, front_camera(8, 8)), engine::Error);
    pass().settings().low_res_tile_size = 8;
    // The pass recovers: the next frame is drawn.
    EXPECT_EQ(render(needles, front_camera(16, 16), 0.5f).width, 16);
}
