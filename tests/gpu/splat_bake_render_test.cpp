// A baked LOD asset through the whole product: splat_synth content → bake (CPU) → PLY → the plugin's
// GPU selection and renderer. Seen small, `full` must be closer to the area-averaged reference than
// `baseline`, and at full size it must stay close to baseline.
#include <gtest/gtest.h>

#include <memory>

#include "engine/render/camera.h"
#include "gpu_fixture.h"
#include "gpu/gpu_scene.h"
#include "passes/splat_pass.h"
#include "splat_lod/bake/bake.h"
#include "splat_lod/bake/bake_cameras.h"
#include "splat_lod/eval/camera_set.h"
#include "splat_lod/eval/image_metrics.h"
#include "splat_lod/splat_io.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/synth/fine_detail_scene.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace {

namespace eval = splat_lod::eval;

class SplatBakeRenderTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness harness;
};

engine::Image render_mode(engine::test::SplatRenderHarness& harness, const std::shared_ptr<const splat_lod::SplatCloud>& cloud,
                          const engine::CameraView& camera, plugin_msgs::LodMode mode) {
    plugin_msgs::LodSettings lod;
    lod.mode = mode;
    harness.engine().bus().publish(lod);
    return harness.render({cloud}, camera);
}

// A garden in miniature (~10k Gaussians, still full of sub-pixel leaves) baked from 12 cameras.
struct BakedGarden {
    splat_lod::SplatCloud baked;
    splat_lod::bake::BakeSummary summary;
    eval::SceneExtent extent;
};

BakedGarden bake_garden(int refine_iterations) {
    splat_lod::synth::FineDetailOptions synth;
    synth.detail = 0.05f;
    const splat_lod::SplatCloud fine = splat_lod::synth::make_fine_detail_scene(synth);
    BakedGarden garden;
    garden.extent = eval::robust_extent(fine.positions);
    const auto poses = splat_lod::bake::bake_camera_poses("rings:2x6", garden.extent, glm::vec3(0, 1, 0));
    splat_lod::bake::BakeOptions options;
    options.refine_iterations = refine_iterations;
    options.refine_cameras = 6;
    garden.baked = splat_lod::bake::bake_lod(fine, splat_lod::bake::bake_cameras(poses, 256, 192), options, &garden.summary);
    return garden;
}

TEST_F(SplatBakeRenderTest, BakedGardenLooksRightWhenSmallAndStaysExactWhenLarge) {
    const auto [baked, summary, extent] = bake_garden(60);
    const glm::vec3 up(0, 1, 0);
    ASSERT_GT(summary.output_gaussians, summary.input_gaussians);

    // Through the file format, as a user would load it.
    const auto path = engine::test::output_dir("SplatBakeRenderTest") / "garden.lod.ply";
    splat_lod::write_inria_ply(path, baked);
    const auto cloud = std::make_shared<const splat_lod::SplatCloud>(splat_lod::load_splat_file(path));

    // A held-out view (the evaluation's orbit, not the bake's rings).
    const auto pose = eval::orbit_poses(extent, up, 1).front();
    const auto reference = eval::to_float(render_mode(harness, cloud, eval::make_view(pose, 256, 192), plugin_msgs::LodMode::baseline));
    const auto full_large = eval::to_float(render_mode(harness, cloud, eval::make_view(pose, 256, 192), plugin_msgs::LodMode::full));
    const double large = eval::psnr(full_large, reference);
    EXPECT_GE(large, 35.0);

    const int k = 16;
    const auto target = eval::area_average(reference, k);
    const auto small_view = eval::make_view(pose, 256 / k, 192 / k);
    const double baseline_small =
        eval::psnr(eval::to_float(render_mode(harness, cloud, small_view, plugin_msgs::LodMode::baseline)), target);
    const double full_small = eval::psnr(eval::to_float(render_mode(harness, cloud, small_view, plugin_msgs::LodMode::full)), target);
    RecordProperty("psnr_1x", std::to_string(large));
    RecordProperty("psnr_16x_baseline", std::to_string(baseline_small));
    RecordProperty("psnr_16x_full", std::to_string(full_small));
    EXPECT_GT(full_small, baseline_small + 1.0) << "baseline " << baseline_small << " dB, full " << full_small << " dB";
    const auto& statistics = splat_lod::find_splat_pass(harness.engine().renderer())->latest_statistics();
    ASSERT_TRUE(statistics.has_value());
    EXPECT_GT(statistics->per_level[1] + statistics->per_level[2] + statistics->per_level[3], 0u);
}

TEST_F(SplatBakeRenderTest, ClusterSkippingChangesNothingButTheWork) {
    // Skipping whole workgroups of too-small Gaussians must be invisible: the same bytes and the
    // same per-level counts with it on and off, near and far, in every mode.
    const auto garden = bake_garden(0);
    const auto& extent = garden.extent;
    const glm::vec3 up(0, 1, 0);
    const auto cloud = std::make_shared<const splat_lod::SplatCloud>(garden.baked);
    auto* pass = splat_lod::find_splat_pass(harness.engine().renderer());
    const auto pose = eval::orbit_poses(extent, up, 1).front();
    bool skipped_somewhere = false;
    for (const float distance : {1.0f, 8.0f, 64.0f})
        for (const auto mode : {plugin_msgs::LodMode::full, plugin_msgs::LodMode::filter_small}) {
            SCOPED_TRACE("distance " + std::to_string(distance) + ", " + std::string(plugin_msgs::to_string(mode)));
            const auto view = eval::make_view(eval::dolly(pose, distance), 128, 96);
            pass->settings.cluster_skipping = false;
            const auto without = render_mode(harness, cloud, view, mode);
            const auto counts_without = pass->latest_statistics()->per_level;
            pass->settings.cluster_skipping = true;
            const auto with = render_mode(harness, cloud, view, mode);
            EXPECT_EQ(with.rgba, without.rgba);
            EXPECT_EQ(pass->latest_statistics()->per_level, counts_without);
            if (pass->latest_statistics()->skipped > 0) skipped_somewhere = true;
        }
    EXPECT_TRUE(skipped_somewhere) << "far away, whole clusters of small Gaussians are skipped";
}

}  // namespace
