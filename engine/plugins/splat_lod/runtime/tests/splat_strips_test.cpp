// Strips of tile rows (SplatPassSettings::frame_memory_limit, docs/gpu_storage.md "Strips"): a frame drawn
// in strips keeps its buffers within the limit and draws what it draws in one piece: the same pixels,
// splat depths, picks and statistics, natively and below render scale 1.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <vector>

#include "engine/render/render_target.h"
#include "engine/scene/scene.h"
#include "gpu_fixture.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "splat_test_scenes.h"
#include "test_support.h"

using engine::test::GaussianSpec;

namespace {

// `count` Gaussians of many sizes spread evenly over the view.
std::shared_ptr<const splat_lod::SplatCloud> field(int count) {
    std::vector<GaussianSpec> specs;
    for (int i = 0; i < count; ++i) {
        const float t = static_cast<float>(i);
        const float u = 0.5f + 0.5f * std::sin(t * 12.9898f), v = 0.5f + 0.5f * std::sin(t * 78.233f);
        specs.push_back({{4.6f * (u - 0.5f), 3.4f * (v - 0.5f), 0.6f * std::sin(t * 0.37f)},
                         glm::vec3(-4.2f + 1.4f * (0.5f + 0.5f * std::sin(t * 3.1f))),
                         {1.0f, 0.2f * std::sin(t), 0.1f * std::cos(t), 0.0f},
                         0.5f + 1.5f * std::sin(t * 0.9f),
                         {0.5f + 0.4f * std::sin(t), 0.5f + 0.4f * std::cos(t * 1.1f), 0.5f + 0.3f * v}});
    }
    return std::make_shared<const splat_lod::SplatCloud>(engine::test::make_cloud(specs));
}

struct Drawn {
    engine::Image image;
    splat_lod::SplatDepth depth;
    plugin_msgs::SplatStatistics statistics;
    splat_lod::SplatMemory memory;
    std::vector<engine::PickResult> picks;
};

class SplatStripsTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness harness;
    splat_lod::SplatRenderer pass{harness.engine().renderer()};
    engine::CameraView camera =
        engine::make_look_at_camera({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 192, 144, 0.1f, 100.0f);
    std::unique_ptr<engine::Scene> scene = std::make_unique<engine::Scene>();
    std::vector<glm::ivec2> picked{{10, 5}, {96, 70}, {150, 100}, {30, 140}, {191, 143}, {64, 36}};

    void SetUp() override {
        GpuTest::SetUp();
        auto component = std::make_unique<splat_lod::SplatComponent>();
        component->cloud = field(9000);
        scene->root().add_child("field").attach(std::move(component));
        pass.settings().splat_depth = true;
    }

    // Draws `frames` frames with `limit` and picks on the last.
    Drawn draw(std::uint64_t limit, int frames = 1) {
        pass.settings().frame_memory_limit = limit;
        engine::RenderTarget target(camera.width, camera.height);
        for (int f = 1; f < frames; ++f) splat_lod::render_complete(harness.engine(), *scene, camera, target);
        std::vector<std::uint64_t> tickets;
        for (const glm::ivec2 p : picked) tickets.push_back(pass.pick(p));
        Drawn d;
        d.statistics = splat_lod::render_complete(harness.engine(), *scene, camera, target);
        d.image = target.read_color();
        d.depth = pass.read_splat_depth();
        d.memory = pass.memory();
        for (const std::uint64_t t : tickets) d.picks.push_back(pass.pick_result(t, true));
        return d;
    }
};

void expect_same_frame(const Drawn& whole, const Drawn& strips) {
    EXPECT_EQ(strips.image.rgba, whole.image.rgba) << "the same pixels";
    EXPECT_EQ(strips.depth.median, whole.depth.median);
    EXPECT_EQ(strips.depth.expected, whole.depth.expected);
    EXPECT_EQ(strips.statistics.visible, whole.statistics.visible) << "each splat counted once";
    EXPECT_EQ(strips.statistics.per_level, whole.statistics.per_level);
    EXPECT_EQ(strips.statistics.tile_splat_pairs, whole.statistics.tile_splat_pairs);
    EXPECT_EQ(strips.statistics.culled, whole.statistics.culled);
    EXPECT_EQ(strips.statistics.skipped, whole.statistics.skipped);
    ASSERT_EQ(strips.picks.size(), whole.picks.size());
    for (std::size_t k = 0; k < whole.picks.size(); ++k) {
        ASSERT_TRUE(strips.picks[k].ready);
        ASSERT_EQ(strips.picks[k].hit.has_value(), whole.picks[k].hit.has_value()) << "pick " << k;
        if (whole.picks[k].hit) {
            EXPECT_EQ(strips.picks[k].hit->position, whole.picks[k].hit->position) << k;
        }
    }
}

}  // namespace

// With (depth bits, tile) keys every tile sorts its splats as in one piece, so the frame is the same bit
// for bit, natively and upscaled, and the buffers that follow the view stay within the limit.
TEST_F(SplatStripsTest, StripsDrawTheSameFrameWithinTheLimit) {
    pass.settings().compact_sort_keys = false;
    for (const float scale : {1.0f, 0.5f}) {
        SCOPED_TRACE(scale);
        harness.edit_lod([&](plugin_msgs::LodSettings& lod) { lod.render_scale = scale; });
        const Drawn whole = draw(0, 2);
        ASSERT_EQ(whole.memory.strips, 1u);
        ASSERT_GT(whole.statistics.visible, 5000u);
        ASSERT_GT(whole.statistics.tile_splat_pairs, whole.statistics.visible) << "splats that span tiles";
        ASSERT_GE(
            std::count_if(whole.picks.begin(), whole.picks.end(), [](const auto& p) { return p.hit.has_value(); }), 3);
        const std::uint64_t limit = whole.memory.view_bytes / 3;
        const Drawn strips = draw(limit, 2);
        EXPECT_GE(strips.memory.strips, 3u);
        EXPECT_LE(strips.memory.view_bytes, limit);
        expect_same_frame(whole, strips);
    }
}

// The first frame with a limit has no frame before it to plan by: a strip that needs more than the room
// is split (its selection run again) until each fits, and the frame is still the same.
TEST_F(SplatStripsTest, AStripThatNeedsMoreIsSplit) {
    pass.settings().compact_sort_keys = false;
    const Drawn whole = draw(0, 2);
    engine::test::SplatRenderHarness fresh;
    splat_lod::SplatRenderer other(fresh.engine().renderer());
    other.settings().compact_sort_keys = false;
    other.settings().frame_memory_limit = whole.memory.view_bytes / 4;
    engine::RenderTarget target(camera.width, camera.height);
    fresh.engine().renderer().render(*scene, camera, target);
    const splat_lod::SplatMemory first = other.memory();
    EXPECT_GE(first.strips, 4u);
    EXPECT_GT(first.selection_runs, 1u) << "strips split on the way";
    EXPECT_LE(first.view_bytes, whole.memory.view_bytes / 4);
    EXPECT_EQ(target.read_color().rgba, whole.image.rgba);
}

// A limit below what one tile row needs: every row is a strip of its own, and the buffers grow past the
// limit to hold it rather than drop a splat.
TEST_F(SplatStripsTest, ALimitBelowOneRowDrawsRowByRow) {
    pass.settings().compact_sort_keys = false;
    const Drawn whole = draw(0, 2);
    const Drawn rows = draw(1, 2);
    EXPECT_EQ(rows.memory.strips, 9u) << "144 px in 16 px rows";
    EXPECT_GT(rows.memory.view_bytes, 1u);
    expect_same_frame(whole, rows);
}

// With one-word keys each strip quantises depth over the depth range of the strips drawn so far, so
// splats at nearly the same depth may swap within a tile; the pixels stay within one step of 255.
TEST_F(SplatStripsTest, OneWordKeysStayWithinAStep) {
    const Drawn whole = draw(0, 2);
    const Drawn strips = draw(whole.memory.view_bytes / 3, 2);
    EXPECT_GE(strips.memory.strips, 3u);
    int worst = 0;
    for (std::size_t i = 0; i < whole.image.rgba.size(); ++i)
        worst = std::max(worst, std::abs(int(whole.image.rgba[i]) - int(strips.image.rgba[i])));
    EXPECT_LE(worst, 1);
    EXPECT_EQ(strips.statistics.visible, whole.statistics.visible);
    EXPECT_EQ(strips.statistics.tile_splat_pairs, whole.statistics.tile_splat_pairs);
}

// Under a splat budget the budget chooses over the whole view: the frame is one strip whatever the limit.
TEST_F(SplatStripsTest, ABudgetDrawsOneStrip) {
    harness.edit_lod([](plugin_msgs::LodSettings& lod) { lod.splat_budget = 4000; });
    const Drawn whole = draw(0, 2);
    const Drawn limited = draw(whole.memory.view_bytes / 4, 2);
    EXPECT_EQ(limited.memory.strips, 1u);
    EXPECT_EQ(limited.image.rgba, whole.image.rgba);
}
