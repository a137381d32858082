// The splats' depth (docs/algorithms.md §1, "Depth") against the double-precision CPU reference, and the
// view depth the pass leaves in the target for the passes after it: the nearer of the meshes' and the
// splats' median depth, at render scale 1 and upscaled.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/render/image.h"
#include "engine/render/render_target.h"
#include "engine/render/scene_camera.h"
#include "engine/scene/builtin_components.h"
#include "engine/scene/scene_loader.h"
#include "gpu_fixture.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_renderer.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace ref = splat_lod::reference;

namespace {

// Mean absolute error of `gpu` against `cpu` over the pixels where the reference's accumulated opacity is
// at least ½ and both depths are finite, against the range of the reference's depths there; `unmatched`
// counts those pixels where only one of the two is finite.
struct DepthError {
    double mean = 0.0, range = 0.0;
    std::size_t pixels = 0, unmatched = 0;
    double relative() const { return range > 0.0 ? mean / range : 0.0; }
};

DepthError depth_error(const std::vector<float>& gpu, const std::vector<double>& cpu,
                       const std::vector<double>& alpha) {
    DepthError e;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0;
    for (std::size_t p = 0; p < cpu.size(); ++p) {
        if (alpha[p] < 0.5) continue;
        const bool a = std::isfinite(gpu[p]), b = std::isfinite(cpu[p]);
        if (a != b) ++e.unmatched;
        if (!a || !b) continue;
        sum += std::abs(static_cast<double>(gpu[p]) - cpu[p]);
        lo = std::min(lo, cpu[p]);
        hi = std::max(hi, cpu[p]);
        ++e.pixels;
    }
    if (e.pixels > 0) {
        e.mean = sum / static_cast<double>(e.pixels);
        e.range = hi - lo;
    }
    return e;
}

class SplatDepthTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness harness;
    splat_lod::SplatRenderer pass{harness.engine().renderer()};

    void SetUp() override {
        GpuTest::SetUp();
        pass.settings().splat_depth = true;
    }
};

}  // namespace

// Done-when of the depth (issue: depth for later passes): on every real scene, the median and the
// expected depth within 0.5 % of the depth range of the reference's where its accumulated opacity is
// at least ½.
TEST_F(SplatDepthTest, RealScenesMatchTheReferenceDepth) {
    ENGINE_REQUIRE_SHARED_DATA();
    for (const auto& scene : engine::test::real_splat_scenes()) {
        SCOPED_TRACE(scene.name);
        const auto cloud = std::make_shared<const splat_lod::SplatCloud>(splat_lod::load_splat_file(scene.path));
        const auto camera = engine::test::orbit_cameras(*cloud, scene.up, 1, 200, 150).front();
        harness.render({cloud}, camera);
        const splat_lod::SplatDepth gpu = pass.read_splat_depth();
        ASSERT_EQ(gpu.width, 200);
        const ref::ReferenceInstance instance{cloud.get(), glm::dmat4(1.0), splat_lod::kMaxShDegree};
        const ref::ReferenceImage cpu = ref::render_reference(std::span(&instance, 1), camera, {});
        const DepthError median = depth_error(gpu.median, cpu.depth_median, cpu.alpha);
        const DepthError expected = depth_error(gpu.expected, cpu.depth_expected, cpu.alpha);
        EXPECT_GT(median.pixels, 2000u);
        EXPECT_LT(median.relative(), 0.005) << median.mean << " of a range of " << median.range;
        EXPECT_LT(expected.relative(), 0.005) << expected.mean << " of a range of " << expected.range;
        EXPECT_LT(median.unmatched, median.pixels / 200) << "pixels with a median on one side only";
        EXPECT_EQ(expected.unmatched, 0u);
        RecordProperty(scene.name + "_median_mae_pct", std::to_string(100.0 * median.relative()));
        RecordProperty(scene.name + "_expected_mae_pct", std::to_string(100.0 * expected.relative()));
    }
}

// The view depth after the splat pass is min(mesh depth, the splats' median depth) at every pixel, at
// render scale 1 and upscaled; the box in front of the biker keeps its own depth, the splats in front
// of the box behind him put theirs, and at render scale 1 the median matches the reference composited
// over the same mesh layer.
TEST_F(SplatDepthTest, ViewDepthIsTheNearerOfMeshAndSplats) {
    auto& engine = harness.engine();
    const auto scene_file = engine::test::repo_dir() / "content/scenes/biker_with_boxes.json";
    const auto full = engine.load_scene(scene_file);
    auto meshes_only = engine.load_scene(scene_file);
    auto* biker = meshes_only->find_node("biker");
    auto* splat = biker->find_component<splat_lod::SplatComponent>();
    const auto cloud = splat->cloud;
    const glm::mat4 model = biker->world_matrix();
    splat->cloud = std::make_shared<const splat_lod::SplatCloud>();
    const int w = 192, h = 144;
    const auto camera = *engine::scene_camera(*full, "", w, h);
    engine::RenderTarget target(w, h);
    engine.renderer().render(*meshes_only, camera, target);
    const ref::MeshLayer layer = engine::test::mesh_layer(target);
    const std::vector<float> mesh = target.read_view_depth();
    const ref::ReferenceInstance instance{cloud.get(), glm::dmat4(model), splat_lod::kMaxShDegree};
    const ref::ReferenceImage cpu = ref::render_reference(std::span(&instance, 1), camera, {}, &layer);

    for (const float scale : {1.0f, 1.0f / 3.0f}) {
        SCOPED_TRACE(scale);
        harness.edit_lod([&](plugin_msgs::LodSettings& lod) { lod.render_scale = scale; });
        engine.renderer().render(*full, camera, target);
        const std::vector<float> merged = target.read_view_depth();
        const splat_lod::SplatDepth splats = pass.read_splat_depth();
        ASSERT_EQ(splats.median.size(), merged.size());
        std::size_t splat_nearer = 0, mesh_kept = 0;
        for (std::size_t p = 0; p < merged.size(); ++p) {
            ASSERT_EQ(merged[p], std::min(mesh[p], splats.median[p])) << "pixel " << p;
            splat_nearer += splats.median[p] < mesh[p] ? 1 : 0;
            mesh_kept += std::isfinite(mesh[p]) && merged[p] == mesh[p] ? 1 : 0;
        }
        EXPECT_GT(splat_nearer, merged.size() / 20);
        EXPECT_GT(mesh_kept, merged.size() / 20);
        // Against the native reference: exact but for rounding natively; upscaled, each pixel has its
        // texel's depth, off at silhouettes by up to the texel's spread (recorded, not a bar).
        const DepthError e = depth_error(splats.median, cpu.depth_median, cpu.alpha);
        const std::string name = scale == 1.0f ? "native" : "upscaled_3x";
        RecordProperty(name + "_median_mae_pct", std::to_string(100.0 * e.relative()));
        RecordProperty(name + "_median_unmatched", std::to_string(e.unmatched) + " of " + std::to_string(e.pixels));
        if (scale == 1.0f) {
            EXPECT_LT(e.relative(), 0.005) << e.mean << " of a range of " << e.range;
        }
    }
    harness.edit_lod([](plugin_msgs::LodSettings& lod) { lod.render_scale = 1.0f; });
}

// A mesh drawn after the splats (MeshComponent::late) is hidden where the splats' median depth is nearer
// and drawn over them elsewhere: every pixel of the frame is either the frame without the late boxes
// or the boxes alone, by which of the two depths is nearer, and the view depth is the nearer one.
// The boxes of biker_with_boxes, one in front of the biker and one behind him, made late.
TEST_F(SplatDepthTest, ALateMeshIsHiddenBehindTheSplatsInFrontOfIt) {
    auto& engine = harness.engine();
    const auto scene_file = engine::test::repo_dir() / "content/scenes/biker_with_boxes.json";
    const int w = 192, h = 144;
    const auto load = [&](bool splats, bool ground, bool boxes, bool late) {
        auto scene = engine.load_scene(scene_file);
        if (!splats)
            scene->find_node("biker")->find_component<splat_lod::SplatComponent>()->cloud =
                std::make_shared<const splat_lod::SplatCloud>();
        if (!ground) scene->find_node("ground")->find_component<engine::MeshComponent>()->mesh = nullptr;
        for (const char* name : {"box_front", "box_behind"}) {
            auto* box = scene->find_node(name)->find_component<engine::MeshComponent>();
            box->late = late;
            if (!boxes) box->mesh = nullptr;
        }
        return scene;
    };
    const auto full = load(true, true, true, true);
    const auto camera = *engine::scene_camera(*full, "", w, h);
    engine::RenderTarget target(w, h);
    engine.renderer().render(*load(true, true, false, false), camera, target);  // before the late pass
    const engine::Image before = target.read_color();
    const std::vector<float> surfaces = target.read_view_depth();
    engine.renderer().render(*load(false, false, true, false), camera, target);  // the boxes alone
    const engine::Image boxes = target.read_color();
    const std::vector<float> box_depth = target.read_view_depth();
    engine.renderer().render(*full, camera, target);
    const engine::Image frame = target.read_color();
    const std::vector<float> depth = target.read_view_depth();

    std::size_t drawn = 0, hidden = 0;
    for (std::size_t p = 0; p < depth.size(); ++p) {
        if (std::isfinite(box_depth[p]) && std::abs(box_depth[p] - surfaces[p]) <= 1e-4f * box_depth[p]) continue;
        const bool box_nearer = box_depth[p] < surfaces[p];
        const engine::Image& expected = box_nearer ? boxes : before;
        for (std::size_t c = 0; c < 4; ++c) ASSERT_EQ(frame.rgba[4 * p + c], expected.rgba[4 * p + c]) << "pixel " << p;
        ASSERT_EQ(depth[p], box_nearer ? box_depth[p] : surfaces[p]) << "pixel " << p;
        drawn += box_nearer ? 1 : 0;
        hidden += std::isfinite(box_depth[p]) && !box_nearer ? 1 : 0;
    }
    // Both boxes are partly in front of the biker's splats and partly behind them or the ground.
    EXPECT_GT(drawn, depth.size() / 50);
    EXPECT_GT(hidden, depth.size() / 50);
    EXPECT_TRUE(engine::test::matches_golden(frame, "splat_late_mesh_biker_boxes"));
}
