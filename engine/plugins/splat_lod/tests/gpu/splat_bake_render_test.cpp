// A baked LOD asset through the whole product: splat_synth content → bake (CPU) → PLY → the plugin's
// GPU selection and renderer. Seen small, `full` must be closer to the area-averaged reference than
// `baseline`, and at full size it must stay close to baseline.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "engine/render/camera.h"
#include "gpu_fixture.h"
#include "splat_lod/bake/bake.h"
#include "splat_lod/bake/bake_cameras.h"
#include "splat_lod/core/camera_set.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/eval/image_metrics.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "splat_lod/synth/fine_detail_scene.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace {

namespace eval = splat_lod::eval;

class SplatBakeRenderTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness harness;
};

engine::Image render_rule(engine::test::SplatRenderHarness& harness,
                          const std::shared_ptr<const splat_lod::SplatCloud>& cloud, const engine::CameraView& camera,
                          const plugin_msgs::LodRule& rule, std::uint32_t splat_budget = 0, float render_scale = 1.0f) {
    plugin_msgs::LodSettings lod;
    lod.rule = rule;
    lod.splat_budget = splat_budget;
    lod.render_scale = render_scale;
    harness.engine().bus().publish(lod);
    return harness.render({cloud}, camera);
}

engine::Image render_mode(engine::test::SplatRenderHarness& harness,
                          const std::shared_ptr<const splat_lod::SplatCloud>& cloud, const engine::CameraView& camera,
                          plugin_msgs::LodMode mode, std::uint32_t splat_budget = 0, float render_scale = 1.0f) {
    plugin_msgs::LodRule rule;
    rule.mode = mode;
    return render_rule(harness, cloud, camera, rule, splat_budget, render_scale);
}

// The rules whose selection skipping and budgets must not change: full (its default band and
// placement), full with a one-octave band inside the hard rule's ranges and centred on the switches
// (fine Gaussians drawn past their switch), and filter_small.
std::vector<plugin_msgs::LodRule> skipping_rules() {
    plugin_msgs::LodRule full, inside, centred, filter_small;
    inside.transition_band = 1.0f;
    inside.transition_placement = plugin_msgs::TransitionPlacement::inside;
    centred.transition_band = 1.0f;
    centred.transition_placement = plugin_msgs::TransitionPlacement::centred;
    filter_small.mode = plugin_msgs::LodMode::filter_small;
    return {full, inside, centred, filter_small};
}

std::string rule_name(const plugin_msgs::LodRule& rule) {
    return std::string(plugin_msgs::to_string(rule.mode)) + " band " + std::to_string(rule.transition_band) + " " +
           std::string(plugin_msgs::to_string(rule.transition_placement));
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
    garden.baked =
        splat_lod::bake::bake_lod(fine, splat_lod::bake::bake_cameras(poses, 256, 192), options, &garden.summary);
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
    const auto reference =
        eval::to_float(render_mode(harness, cloud, eval::make_view(pose, 256, 192), plugin_msgs::LodMode::baseline));
    const auto full_large =
        eval::to_float(render_mode(harness, cloud, eval::make_view(pose, 256, 192), plugin_msgs::LodMode::full));
    const double large = eval::psnr(full_large, reference);
    EXPECT_GE(large, 35.0);

    const int k = 16;
    const auto target = eval::area_average(reference, k);
    const auto small_view = eval::make_view(pose, 256 / k, 192 / k);
    const double baseline_small =
        eval::psnr(eval::to_float(render_mode(harness, cloud, small_view, plugin_msgs::LodMode::baseline)), target);
    const double full_small =
        eval::psnr(eval::to_float(render_mode(harness, cloud, small_view, plugin_msgs::LodMode::full)), target);
    RecordProperty("psnr_1x", std::to_string(large));
    RecordProperty("psnr_16x_baseline", std::to_string(baseline_small));
    RecordProperty("psnr_16x_full", std::to_string(full_small));
    EXPECT_GT(full_small, baseline_small + 1.0) << "baseline " << baseline_small << " dB, full " << full_small << " dB";
    const auto& statistics = splat_lod::SplatRenderer(harness.engine().renderer()).latest_statistics();
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
    splat_lod::SplatRenderer pass(harness.engine().renderer());
    const auto pose = eval::orbit_poses(extent, up, 1).front();
    bool skipped_somewhere = false;
    for (const float distance : {1.0f, 8.0f, 64.0f})
        for (const auto& rule : skipping_rules()) {
            SCOPED_TRACE("distance " + std::to_string(distance) + ", " + rule_name(rule));
            const auto view = eval::make_view(eval::dolly(pose, distance), 128, 96);
            pass.settings().cluster_skipping = false;
            const auto without = render_rule(harness, cloud, view, rule);
            const auto counts_without = pass.latest_statistics()->per_level;
            pass.settings().cluster_skipping = true;
            const auto with = render_rule(harness, cloud, view, rule);
            EXPECT_EQ(with.rgba, without.rgba);
            EXPECT_EQ(pass.latest_statistics()->per_level, counts_without);
            if (pass.latest_statistics()->skipped > 0) skipped_somewhere = true;
        }
    EXPECT_TRUE(skipped_somewhere) << "far away, whole clusters of small Gaussians are skipped";
}

// A pose at `eye` looking at `target` (up made orthogonal to the view).
eval::CameraPose look_at(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up_hint, float fov_y) {
    eval::CameraPose pose;
    pose.eye = eye;
    pose.forward = glm::normalize(target - eye);
    pose.up = glm::normalize(up_hint - glm::dot(up_hint, pose.forward) * pose.forward);
    pose.fov_y = fov_y;
    pose.focus_distance = glm::length(target - eye);
    return pose;
}

TEST_F(SplatBakeRenderTest, FrustumCullingChangesNothingButTheWork) {
    // Clusters outside the view are dropped before projection, and that must be invisible: the same
    // bytes and per-level counts with it on and off, from inside the garden looking every way, from
    // outside with it half out of view, in every mode, natively and at a third of the resolution.
    const auto garden = bake_garden(0);
    const auto& extent = garden.extent;
    const glm::vec3 up(0, 1, 0);
    const auto cloud = std::make_shared<const splat_lod::SplatCloud>(garden.baked);
    splat_lod::SplatRenderer pass(harness.engine().renderer());
    std::vector<eval::CameraPose> poses;
    for (int k = 0; k < 4; ++k) {  // inside, looking out in four directions
        const float a = 1.5707963f * static_cast<float>(k);
        poses.push_back(look_at(extent.centre, extent.centre + glm::vec3(std::cos(a), 0.0f, std::sin(a)), up, 0.9f));
    }
    const auto orbit = eval::orbit_poses(extent, up, 1).front();
    const glm::vec3 target = orbit.eye + orbit.forward * orbit.focus_distance;
    const glm::vec3 aside = glm::normalize(glm::cross(orbit.forward, up)) * extent.radius;
    poses.push_back(look_at(orbit.eye, target + aside, up, orbit.fov_y));             // half out of view
    poses.push_back(look_at(orbit.eye, 2.0f * orbit.eye - target, up, orbit.fov_y));  // facing away
    std::uint64_t culled = 0;
    for (std::size_t p = 0; p < poses.size(); ++p)
        for (const auto mode : {plugin_msgs::LodMode::full, plugin_msgs::LodMode::baseline})
            for (const float scale : {1.0f, 1.0f / 3.0f}) {
                SCOPED_TRACE("pose " + std::to_string(p) + ", " + std::string(plugin_msgs::to_string(mode)) +
                             ", render scale " + std::to_string(scale));
                const auto view = eval::make_view(poses[p], 120, 90);
                pass.settings().frustum_culling = false;
                const auto without = render_mode(harness, cloud, view, mode, 0, scale);
                const auto stats_without = *pass.latest_statistics();
                pass.settings().frustum_culling = true;
                const auto with = render_mode(harness, cloud, view, mode, 0, scale);
                EXPECT_EQ(with.rgba, without.rgba);
                EXPECT_EQ(pass.latest_statistics()->per_level, stats_without.per_level);
                EXPECT_EQ(stats_without.culled, 0u);
                culled += pass.latest_statistics()->culled;
            }
    EXPECT_GT(culled, 0u) << "clusters behind and beside the view are culled";
}

TEST_F(SplatBakeRenderTest, FrustumCullingKeepsGaussiansWhoseTailsReachIntoTheView) {
    // A cluster of wide Gaussians just left of the view, their means outside it, their 1/255 tails
    // inside: the bound must not drop them (and far beyond the tails it does).
    const engine::CameraView view =
        eval::make_view(look_at(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0), 1.0472f), 96, 64);
    splat_lod::SplatRenderer pass(harness.engine().renderer());
    for (const float x : {-5.2f, -40.0f}) {
        std::vector<engine::test::GaussianSpec> specs(256);
        for (std::size_t i = 0; i < specs.size(); ++i) {
            specs[i].position = glm::vec3(x, -0.5f + static_cast<float>(i) / 256.0f, 0.0f);
            specs[i].log_scale = glm::vec3(std::log(0.8f));
            specs[i].color = glm::vec3(0.9f, 0.6f, 0.2f);
        }
        const auto cloud = std::make_shared<const splat_lod::SplatCloud>(engine::test::make_cloud(specs));
        pass.settings().frustum_culling = false;
        const auto without = render_mode(harness, cloud, view, plugin_msgs::LodMode::baseline);
        const auto visible_without = pass.latest_statistics()->visible;
        pass.settings().frustum_culling = true;
        const auto with = render_mode(harness, cloud, view, plugin_msgs::LodMode::baseline);
        EXPECT_EQ(with.rgba, without.rgba);
        if (x > -6.0f) {
            EXPECT_GT(visible_without, 0u) << "the tails reach into the image";
            EXPECT_EQ(pass.latest_statistics()->culled, 0u);
        } else {
            EXPECT_EQ(visible_without, 0u);
            EXPECT_EQ(pass.latest_statistics()->culled, 256u) << "far outside, the whole cluster is culled";
        }
    }
}

TEST_F(SplatBakeRenderTest, SplatBudgetIsNeverExceededAndChangesNothingWhenItFits) {
    const auto garden = bake_garden(0);
    const auto cloud = std::make_shared<const splat_lod::SplatCloud>(garden.baked);
    splat_lod::SplatRenderer pass(harness.engine().renderer());
    const auto pose = eval::orbit_poses(garden.extent, glm::vec3(0, 1, 0), 1).front();
    const auto view = eval::make_view(eval::dolly(pose, 0.6f), 128, 96);
    std::vector<plugin_msgs::LodRule> rules = skipping_rules();
    rules.back().mode = plugin_msgs::LodMode::baseline;  // full, full inside, full centred, baseline
    for (const auto& rule : rules) {
        const plugin_msgs::LodMode mode = rule.mode;
        SCOPED_TRACE(rule_name(rule));
        const auto free = render_rule(harness, cloud, view, rule);
        const plugin_msgs::SplatStatistics unbudgeted = *pass.latest_statistics();
        ASSERT_GT(unbudgeted.visible, 1000u);
        EXPECT_EQ(unbudgeted.unbudgeted, unbudgeted.visible);

        // Fits exactly.
        const auto fitting = render_rule(harness, cloud, view, rule, static_cast<std::uint32_t>(unbudgeted.visible));
        EXPECT_EQ(fitting.rgba, free.rgba);
        EXPECT_EQ(pass.latest_statistics()->visible, unbudgeted.visible);
        EXPECT_EQ(pass.latest_statistics()->budget_scale, 1.0);

        double previous_psnr = 1e9;
        for (const double share : {0.7, 0.3, 0.05}) {
            const auto budget = static_cast<std::uint32_t>(share * static_cast<double>(unbudgeted.visible));
            const auto image = render_rule(harness, cloud, view, rule, budget);
            const auto& s = *pass.latest_statistics();
            SCOPED_TRACE("budget " + std::to_string(budget));
            EXPECT_LE(s.visible, budget);
            EXPECT_GT(s.visible, 0u);
            EXPECT_EQ(s.per_level[0] + s.per_level[1] + s.per_level[2] + s.per_level[3], s.visible);
            EXPECT_EQ(s.unbudgeted, unbudgeted.visible);
            EXPECT_GT(s.budget_threshold_px, 0.0);
            if (mode == plugin_msgs::LodMode::baseline) {  // no coarser level to go to: the smallest go
                EXPECT_GT(s.budget_coverage_cut_px, 0.0);
                EXPECT_EQ(s.budget_scale, 1.0);
            } else
                EXPECT_TRUE(s.budget_scale > 1.0 || s.budget_coverage_cut_px > 0.0);
            const double psnr = eval::psnr(eval::to_float(image), eval::to_float(free));
            RecordProperty(rule_name(rule) + "_psnr_at_" + std::to_string(share), std::to_string(psnr));
            EXPECT_LE(psnr, previous_psnr + 0.5) << "a smaller budget does not get closer to the free frame";
            previous_psnr = psnr;
        }
        for (const std::uint32_t tiny : {1u, 17u}) {  // even the coarsest cut is too many
            render_rule(harness, cloud, view, rule, tiny);
            EXPECT_LE(pass.latest_statistics()->visible, tiny);
        }
    }
}

}  // namespace
