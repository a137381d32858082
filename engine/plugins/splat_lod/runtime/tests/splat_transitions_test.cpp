// Smooth transitions on the GPU against the CPU's weights (docs/algorithms.md §3, "Smooth transitions"):
// the splat pass scales each selected Gaussian's opacity by splat_lod::lod_weight, so its image equals
// the reference render of the cloud with opacities scaled by the CPU's weights.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "engine/render/scene_camera.h"
#include "splat_lod/core/compact_gaussians.h"
#include "splat_lod/core/lod_selection.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/splat_renderer.h"
#include "splat_pipeline_fixture.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace ref = splat_lod::reference;
using plugin_msgs::TransitionPlacement;
using splat_lod::LevelHandover;

namespace {

class SplatTransitionsTest : public SplatPipelineTest {
protected:
    const engine::CameraView camera =
        engine::make_look_at_camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 160, 120, 0.1f, 100.0f);
    const ref::ReferenceCamera ref_camera = ref::make_reference_camera(camera);
    const ref::ReferenceSettings settings;
    splat_lod::SplatRenderer pass{harness.engine().renderer()};

    // This view's coverage of Gaussian i of `cloud` (undilated, as the rule takes it).
    double coverage(const splat_lod::SplatCloud& cloud, std::size_t i) const {
        const auto p = ref::project_gaussian(cloud, i, glm::dmat4(1.0), ref_camera, settings);
        const glm::dvec3 c = p.cov2d - glm::dvec3(settings.dilation, 0.0, settings.dilation);
        return splat_lod::pixel_coverage(c.x, c.y, c.z, p.opacity);
    }

    // 400 Gaussians on four levels whose switches spread from 1.2 bands past this view's coverage to 1.2
    // bands before it (the band `rule` gives a cloud of this handover): wherever the band lies against
    // its switch, many are inside it.
    splat_lod::SplatCloud banded(const splat_lod::LodRule& rule, LevelHandover handover,
                                 glm::vec3 offset = glm::vec3(0.0f)) const {
        std::vector<engine::test::GaussianSpec> specs;
        for (int i = 0; i < 400; ++i) {
            const float t = static_cast<float>(i);
            specs.push_back(
                {glm::vec3(1.6f * std::sin(t * 1.3f), 1.2f * std::cos(t * 0.7f), -1.5f * std::sin(t * 0.23f)) + offset,
                 glm::vec3(-3.5f + 0.8f * std::sin(t * 0.5f)),
                 {1, 0, 0, 0},
                 1.5f,
                 {0.5f + 0.5f * std::sin(t), 0.4f, 0.5f + 0.5f * std::cos(t)}});
        }
        auto cloud = engine::test::make_cloud(specs);
        cloud.level_handover = handover;
        const double band = rule.for_asset(handover).transition_band;
        for (std::size_t i = 0; i < cloud.size(); ++i) {
            const double s = coverage(cloud, i);
            cloud.lod_level[i] = static_cast<std::uint8_t>(1 + i % 4);
            const double octaves = band * 1.2 * std::sin(0.37 * static_cast<double>(i));
            cloud.coverage_max[i] = static_cast<float>(s / (rule.rel_max * std::exp2(octaves)));
            cloud.coverage_min[i] = (i % 2 == 0) ? -1.0f : static_cast<float>(s / (rule.rel_min * std::exp2(octaves)));
        }
        return cloud;
    }

    // The Gaussians the CPU draws of what the GPU stores (compact: quantised bounds and opacities), each
    // with its weight (by the rule resolved for the cloud's handover) in its opacity; `partial` counts
    // those inside a band.
    splat_lod::SplatCloud cpu_weighted(const splat_lod::SplatCloud& cloud, const splat_lod::LodRule& rule,
                                       int& partial) const {
        const splat_lod::LodRule asset = rule.for_asset(cloud.level_handover);
        auto weighted = splat_lod::compact_round_trip(cloud, cloud.sh_degree);
        std::vector<std::uint8_t> keep(cloud.size());
        for (std::size_t i = 0; i < weighted.size(); ++i) {
            const auto p = ref::project_gaussian(weighted, i, glm::dmat4(1.0), ref_camera, settings);
            const double w = splat_lod::lod_weight(asset, weighted.lod_level[i], coverage(weighted, i),
                                                   weighted.coverage_min[i], weighted.coverage_max[i]);
            if (w > 0.0 && w < 1.0) ++partial;
            const double opacity = p.opacity * w;
            keep[i] = p.drawn() && opacity > 1.0 / 255.0;
            if (keep[i]) weighted.opacity_logits[i] = static_cast<float>(std::log(opacity / (1.0 - opacity)));
        }
        weighted.keep_only(keep);
        return weighted;
    }

    // The rule the pass holds after publishing `placement` with the default bands.
    splat_lod::LodRule publish(TransitionPlacement placement) {
        plugin_msgs::LodSettings lod;  // full, the default bands
        lod.rule.transition_placement = placement;
        harness.engine().bus().publish(lod);
        return pass.lod().rule;
    }
};

}  // namespace

// Every placement of the band (inside; before; centred on the switches; staggered), and the default `auto`, which
// resolves it per cloud by its level handover (LodRule::for_asset), draws the CPU's weights; the same
// frame drawn twice is the same bytes (a pure function of the view).
TEST_F(SplatTransitionsTest, EachPlacementScalesOpacityByTheCpuWeight) {
    const std::vector<std::pair<TransitionPlacement, LevelHandover>> cases{
        {TransitionPlacement::inside, LevelHandover::overlapping},
        {TransitionPlacement::before, LevelHandover::unknown},
        {TransitionPlacement::centred, LevelHandover::abutting},
        {TransitionPlacement::staggered, LevelHandover::overlapping},
        {TransitionPlacement::automatic, LevelHandover::overlapping},
        {TransitionPlacement::automatic, LevelHandover::abutting},
        {TransitionPlacement::automatic, LevelHandover::unknown}};
    for (const auto& [placement, handover] : cases) {
        SCOPED_TRACE(std::string(plugin_msgs::to_string(placement)) + ", levels " +
                     splat_lod::level_handover_name(handover));
        const splat_lod::LodRule rule = publish(placement);
        ASSERT_EQ(rule.transition_band, plugin_msgs::LodRule::kDefaultTransitionBand);
        ASSERT_EQ(rule.transition_placement, placement);
        const auto cloud = shared(banded(rule, handover));
        int partial = 0;
        const auto weighted = cpu_weighted(*cloud, rule, partial);
        EXPECT_GT(partial, 60) << "the case is not vacuous: many Gaussians are inside the band";
        const auto gpu = harness.render({cloud}, camera);
        EXPECT_GE(engine::compare_images(gpu, reference(weighted, camera)).psnr_db, 40.0);
        // Float on the GPU, double here: a weight at the 1/255 edge may fall either way.
        EXPECT_NEAR(static_cast<double>(pass.latest_statistics()->visible), static_cast<double>(weighted.size()), 2.0);
        EXPECT_EQ(harness.render({cloud}, camera).rgba, gpu.rgba) << "the same frame twice";
    }
}

// Clouds of the three handovers in one frame under auto, moved a little apart (no two Gaussians at one
// depth): each fades by its own kind.
TEST_F(SplatTransitionsTest, AutoFadesEachCloudByItsOwnHandover) {
    const splat_lod::LodRule rule = publish(TransitionPlacement::automatic);
    auto overlapping = banded(rule, LevelHandover::overlapping);
    const auto abutting = banded(rule, LevelHandover::abutting, {0.05f, 0.03f, -0.02f});
    const auto unknown = banded(rule, LevelHandover::unknown, {-0.04f, 0.02f, 0.03f});
    int partial = 0;
    auto expected = cpu_weighted(overlapping, rule, partial);
    splat_lod::append_cloud(expected, cpu_weighted(abutting, rule, partial));
    splat_lod::append_cloud(expected, cpu_weighted(unknown, rule, partial));
    EXPECT_GT(partial, 180);
    const auto gpu = harness.render({shared(overlapping), shared(abutting), shared(unknown)}, camera);
    EXPECT_GE(engine::compare_images(gpu, reference(expected, camera)).psnr_db, 40.0);
    EXPECT_NEAR(static_cast<double>(pass.latest_statistics()->visible), static_cast<double>(expected.size()), 6.0);
    // All drawn as the abutting kind is another image.
    overlapping.level_handover = LevelHandover::abutting;
    auto unknown_as_abutting = unknown;
    unknown_as_abutting.level_handover = LevelHandover::abutting;
    auto all_abutting = cpu_weighted(overlapping, rule, partial);
    splat_lod::append_cloud(all_abutting, cpu_weighted(abutting, rule, partial));
    splat_lod::append_cloud(all_abutting, cpu_weighted(unknown_as_abutting, rule, partial));
    EXPECT_LT(engine::compare_images(reference(all_abutting, camera), reference(expected, camera)).psnr_db, 40.0);
}

// Hard switching (band 0) draws another image from the same cloud than the band placed before, and the
// mode full_hard is that image whatever the band and placement.
TEST_F(SplatTransitionsTest, HardSwitchingIgnoresTheBand) {
    const auto cloud = shared(banded(publish(TransitionPlacement::before), LevelHandover::unknown));
    const auto smooth_image = harness.render({cloud}, camera);
    plugin_msgs::LodSettings hard;
    hard.rule.transition_band = 0.0f;
    hard.rule.overlap_transition_band = 0.0f;
    harness.engine().bus().publish(hard);
    const auto hard_image = harness.render({cloud}, camera);
    EXPECT_LT(engine::compare_images(hard_image, smooth_image).psnr_db, 40.0);
    plugin_msgs::LodSettings full_hard;
    full_hard.rule.mode = plugin_msgs::LodMode::full_hard;
    full_hard.rule.transition_placement = TransitionPlacement::centred;
    harness.engine().bus().publish(full_hard);
    EXPECT_EQ(harness.render({cloud}, camera).rgba, hard_image.rgba);
}
