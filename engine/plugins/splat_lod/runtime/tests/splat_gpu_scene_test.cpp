// The incremental GPU scene (gpu/gpu_scene.h): clouds that arrive or leave cost only their own
// bytes, freed ranges are reused, and the frame is the same as with the whole set uploaded at once.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/render/render_target.h"
#include "engine/scene/scene.h"
#include "gpu/gpu_scene.h"
#include "gpu_fixture.h"
#include "passes/splat_pass.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_test_scenes.h"
#include "test_support.h"

using engine::test::GaussianSpec;

namespace {

// `count` Gaussians in a slab at depth offset `z` (each cloud its own region of the view).
std::shared_ptr<const splat_lod::SplatCloud> slab(int count, float x, int seed) {
    std::vector<GaussianSpec> specs;
    for (int i = 0; i < count; ++i) {
        const float t = static_cast<float>(i + 1000 * seed);
        specs.push_back({{x + 0.35f * std::sin(t * 1.3f), 0.8f * std::cos(t * 0.7f), 0.4f * std::sin(t * 0.31f)},
                         glm::vec3(-3.4f + 0.5f * std::sin(t)),
                         {1, 0, 0, 0},
                         1.0f + std::sin(t * 0.9f),
                         {0.5f + 0.4f * std::sin(t), 0.5f + 0.4f * std::cos(t * 1.1f), 0.5f}});
    }
    return std::make_shared<const splat_lod::SplatCloud>(engine::test::make_cloud(specs));
}

int max_difference(const engine::Image& a, const engine::Image& b) {
    int worst = 0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) worst = std::max(worst, std::abs(int(a.rgba[i]) - int(b.rgba[i])));
    return worst;
}

class SplatGpuSceneTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness incremental;
    engine::CameraView camera =
        engine::make_look_at_camera({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 128, 96, 0.1f, 100.0f);

    const splat_lod::gpu::GpuScene& scene() {
        return splat_lod::find_splat_pass(incremental.engine().renderer())->scene();
    }
    splat_lod::FrameCounts counts() {
        return splat_lod::find_splat_pass(incremental.engine().renderer())->last_frame_counts();
    }
    // The same clouds rendered by a pass that never saw another set: the reference frame.
    engine::Image from_scratch(const std::vector<std::shared_ptr<const splat_lod::SplatCloud>>& clouds) {
        engine::test::SplatRenderHarness fresh;
        return fresh.render(clouds, camera);
    }
};

}  // namespace

TEST_F(SplatGpuSceneTest, ArrivingCloudsUploadOnlyTheirOwnBytes) {
    const auto a = slab(700, -1.2f, 1), b = slab(300, 0.0f, 2), c = slab(1000, 1.2f, 3);
    incremental.render({a}, camera);
    const std::uint64_t first = scene().last_upload_bytes();
    incremental.render({a}, camera);
    EXPECT_EQ(scene().last_upload_bytes(), 0u) << "an unchanged scene uploads nothing";
    const auto ab = incremental.render({a, b}, camera);
    const std::uint64_t second = scene().last_upload_bytes();
    // Bytes per Gaussian slot: the 20-byte compact record (no SH words at degree 0) + a cluster
    // record and a page codec per 256.
    const auto slot_bytes = [](std::uint64_t count) {
        const std::uint64_t span = (count + 255) / 256 * 256;
        return span * 20 + span / 256 * (sizeof(splat_lod::gpu::GpuCluster) + sizeof(splat_lod::gpu::GpuPageCodec));
    };
    EXPECT_EQ(first, slot_bytes(700));
    EXPECT_EQ(second, slot_bytes(300));
    EXPECT_LE(max_difference(ab, from_scratch({a, b})), 1);
    const auto abc = incremental.render({a, b, c}, camera);
    EXPECT_EQ(scene().last_upload_bytes(), slot_bytes(1000));
    EXPECT_LE(max_difference(abc, from_scratch({a, b, c})), 1);
    EXPECT_EQ(splat_lod::find_splat_pass(incremental.engine().renderer())->latest_statistics()->considered, 2000u);
}

TEST_F(SplatGpuSceneTest, LeavingCloudsFreeTheirRangesForReuse) {
    const auto a = slab(700, -1.2f, 1), b = slab(500, 0.0f, 2), c = slab(900, 1.2f, 3), d = slab(450, 0.6f, 4);
    incremental.render({a, b, c}, camera);
    const std::uint32_t high_water = scene().gaussian_count();
    EXPECT_EQ(high_water, 768u + 512u + 1024u);
    // b leaves: its clusters empty, nothing of it drawn; the frame equals one without b.
    const auto ac = incremental.render({a, c}, camera);
    EXPECT_LE(max_difference(ac, from_scratch({a, c})), 1);
    auto* pass = splat_lod::find_splat_pass(incremental.engine().renderer());
    EXPECT_EQ(pass->latest_statistics()->considered, 1600u);
    EXPECT_EQ(pass->latest_statistics()->skipped, 0u) << "empty ranges are not counted as skipped";
    // d fits b's old range: the buffers do not grow past the old end.
    const auto acd = incremental.render({a, c, d}, camera);
    EXPECT_EQ(scene().gaussian_count(), high_water);
    EXPECT_LE(max_difference(acd, from_scratch({a, c, d})), 1);
    // The last range leaving lowers the end, and an empty scene draws nothing.
    incremental.render({a}, camera);
    EXPECT_EQ(scene().gaussian_count(), 768u);
    EXPECT_EQ(scene().live_gaussians(), 700u);
}

TEST_F(SplatGpuSceneTest, AHigherShDegreeRebuildsAndStaysCorrect) {
    const auto a = slab(400, -0.6f, 1);
    auto with_sh =
        engine::test::make_cloud({{{0.6f, 0.0f, 0.0f}, glm::vec3(-2.5f), {1, 0, 0, 0}, 2.0f, {0.8f, 0.3f, 0.2f}}});
    with_sh.set_sh_degree(1);
    with_sh.sh_rest_at(0, 1, 0) = 0.4f;
    const auto b = std::make_shared<const splat_lod::SplatCloud>(with_sh);
    incremental.render({a}, camera);
    EXPECT_EQ(scene().sh_stride(), 0u) << "compact degree 0: the DC term is in the record";
    const auto ab = incremental.render({a, b}, camera);
    EXPECT_EQ(scene().sh_stride(), 2u) << "degree 1: 2 words";
    EXPECT_LE(max_difference(ab, from_scratch({a, b})), 1);
}

// A cloud may take pages that are not adjacent (what keeps freed memory usable by any later cloud),
// and a reserved scene never grows its buffers.
TEST_F(SplatGpuSceneTest, CloudsSpreadOverScatteredPagesAndReservedBuffersDoNotGrow) {
    const auto a = slab(200, -1.2f, 1), b = slab(250, 0.0f, 2), c = slab(100, 1.2f, 3), d = slab(480, 0.6f, 4);
    auto* pass = splat_lod::find_splat_pass(incremental.engine().renderer());
    incremental.render({a, b, c}, camera);  // pages 0, 1, 2
    incremental.render({b, c}, camera);     // page 0 free
    EXPECT_EQ(scene().free_pages(), 1u);
    const auto bcd = incremental.render({b, c, d}, camera);  // d: pages 0 and 3
    EXPECT_EQ(scene().free_pages(), 0u);
    EXPECT_EQ(scene().gaussian_count(), 4u * 256u);
    EXPECT_LE(max_difference(bcd, from_scratch({b, c, d})), 1);
    EXPECT_EQ(pass->latest_statistics()->considered, 830u);

    engine::test::SplatRenderHarness reserved;
    auto* reserved_pass = splat_lod::find_splat_pass(reserved.engine().renderer());
    reserved.render({a}, camera);
    const_cast<splat_lod::gpu::GpuScene&>(reserved_pass->scene()).reserve(4096, 0);
    const auto& gpu = reserved_pass->scene();
    const auto bytes = [&] {
        return gpu.gaussians().size() + gpu.sh().size() + gpu.clusters().size() + gpu.page_codecs().size();
    };
    const std::size_t reserved_bytes = bytes();
    // Compact at degree 0 stores no SH; the SH buffer keeps one word for its binding.
    EXPECT_EQ(gpu.sh().size(), 4u);
    EXPECT_EQ(reserved_bytes, 16u * gpu.page_bytes() + 4u);
    reserved.render({a, b, c, d}, camera);
    reserved.render({d}, camera);
    reserved.render({a, b, c, d}, camera);
    EXPECT_EQ(bytes(), reserved_bytes) << "the Gaussian, SH, cluster and codec buffers never grew";
}

// A resident component that is hidden keeps its pages but projects nothing: the frame's buffers follow
// what is drawn, and the frame is the one without it.
TEST_F(SplatGpuSceneTest, HiddenComponentsKeepTheirPagesButNotTheirFrameBuffers) {
    const auto a = slab(700, -1.2f, 1), b = slab(6000, 0.0f, 2);
    engine::Scene s;
    s.background = glm::vec3(0.0f);  // as the harness draws
    splat_lod::SplatComponent* shown[2] = {};
    for (const auto& [i, cloud] : {std::pair{0, a}, std::pair{1, b}}) {
        auto component = std::make_unique<splat_lod::SplatComponent>();
        component->cloud = cloud;
        shown[i] = component.get();
        s.root().add_child("splats " + std::to_string(i)).attach(std::move(component));
    }
    engine::RenderTarget target(camera.width, camera.height);
    const auto both = splat_lod::render_complete(incremental.engine(), s, camera, target);
    EXPECT_EQ(counts().splats, both.visible) << "without a budget every projected splat is drawn";
    EXPECT_GT(both.visible, 5000u);
    EXPECT_EQ(counts().pairs, both.tile_splat_pairs);

    shown[1]->visible = false;
    splat_lod::render_complete(incremental.engine(), s, camera, target);
    // A frame starts with the dense array the last one needed: the second frame without b has it smaller.
    const auto hidden = splat_lod::render_complete(incremental.engine(), s, camera, target);
    EXPECT_EQ(scene().pages_in_use(), 27u) << "b stays resident";
    EXPECT_EQ(counts().splats, hidden.visible);
    EXPECT_LE(hidden.visible, 700u);
    EXPECT_EQ(max_difference(target.read_color(), from_scratch({a})), 0);
    // Nine times fewer splats: the dense splats and the keys are made anew at the smaller size.
    EXPECT_LT(hidden.resident_bytes, both.resident_bytes) << "the frame's buffers shrank with what it draws";

    shown[1]->visible = true;
    splat_lod::render_complete(incremental.engine(), s, camera, target);
    EXPECT_EQ(counts().splats, both.visible);
    EXPECT_EQ(max_difference(target.read_color(), from_scratch({a, b})), 0);
}

// Pages that step 1a culls for the view project nothing, and culling them changes no pixel.
TEST_F(SplatGpuSceneTest, PagesOutsideTheViewChangeNothing) {
    const auto inside = slab(700, -1.2f, 1), behind = slab(600, 0.0f, 2);
    const std::vector<glm::mat4> models{glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, 10.0f})};
    const auto culled = incremental.render({inside, behind}, camera, glm::vec3(0.0f), models);
    EXPECT_EQ(scene().pages_in_use(), 6u);
    const splat_lod::FrameCounts with_culling = counts();
    EXPECT_GT(with_culling.splats, 0u);
    EXPECT_LE(with_culling.splats, 700u) << "nothing behind the camera";
    splat_lod::SplatRenderer pass(incremental.engine().renderer());
    pass.settings().frustum_culling = false;
    const auto whole = incremental.render({inside, behind}, camera, glm::vec3(0.0f), models);
    EXPECT_EQ(counts().splats, with_culling.splats);
    EXPECT_EQ(counts().pairs, with_culling.pairs);
    EXPECT_EQ(max_difference(culled, whole), 0);
}
