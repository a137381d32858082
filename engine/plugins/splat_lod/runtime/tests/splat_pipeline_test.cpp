// The GPU splat pipeline against the double-precision CPU reference (docs/algorithms.md §1).
#include <array>
#include <chrono>
#include <cmath>
#include <map>

#include "engine/render/render_target.h"
#include "engine/render/scene_camera.h"
#include "engine/scene/scene_loader.h"
#include "splat_lod/core/compact_gaussians.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "splat_pipeline_fixture.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace ref = splat_lod::reference;
using engine::test::GaussianSpec;

// Done-when of the GPU renderer: >= 40 dB PSNR against the reference on every real scene.
TEST_F(SplatPipelineTest, RealScenesMatchTheReference) {
    ENGINE_REQUIRE_SHARED_DATA();
    const auto out = engine::test::output_dir("splat_pipeline");
    for (const auto& scene : engine::test::real_splat_scenes()) {
        SCOPED_TRACE(scene.name);
        const auto cloud = shared(splat_lod::load_splat_file(scene.path));
        const auto cameras = engine::test::orbit_cameras(*cloud, scene.up, 3, 200, 150);
        for (std::size_t v = 0; v < cameras.size(); ++v) {
            const auto gpu = harness.render({cloud}, cameras[v]);
            const auto cpu = reference(*cloud, cameras[v]);
            const auto d = engine::compare_images(gpu, cpu);
            const std::string name = scene.name + "_view" + std::to_string(v);
            engine::write_png(out / (name + ".gpu.png"), gpu);  // for looking at, pass or fail
            if (d.psnr_db < 40.0) {
                engine::write_png(out / (name + ".reference.png"), cpu);
                engine::write_png(out / (name + ".diff.png"), d.visual);
            }
            EXPECT_GE(d.psnr_db, 40.0) << name << " (images in " << out << ")";
            RecordProperty(name + "_psnr_db", std::to_string(d.psnr_db));
        }
    }
}

TEST_F(SplatPipelineTest, SyntheticSceneMatchesTheReferenceClosely) {
    const auto cloud = shared(engine::test::make_cloud(engine::test::swirl_specs(300, 0.5f, 0.8f)));
    const auto camera = engine::make_look_at_camera({0.5f, 0.8f, 4.0f}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 160,
                                                    120, 0.1f, 100.0f);
    const auto d = engine::compare_images(harness.render({cloud}, camera, {0.1f, 0.2f, 0.3f}),
                                          reference(*cloud, camera, {0.1f, 0.2f, 0.3f}));
    EXPECT_GE(d.psnr_db, 48.0);
    EXPECT_LE(d.max_channel_difference, 3);
}

// Two components whose Gaussians interleave in depth render exactly like one merged cloud.
TEST_F(SplatPipelineTest, SeveralComponentsAreSortedTogether) {
    std::vector<GaussianSpec> red, blue, both;
    for (int i = 0; i < 6; ++i) {
        GaussianSpec s{{0.05f * i, 0.0f, -0.4f * i}, glm::vec3(-1.0f), {1, 0, 0, 0}, 1.0f, {1.0f, 0.1f, 0.1f}};
        if (i % 2 == 1) s.color = {0.1f, 0.1f, 1.0f};
        (i % 2 == 0 ? red : blue).push_back(s);
        both.push_back(s);
    }
    const auto camera =
        engine::make_look_at_camera({0, 0, 3}, {0, 0, -1}, {0, 1, 0}, glm::radians(40.0f), 96, 72, 0.1f, 100.0f);
    const auto merged = harness.render({shared(engine::test::make_cloud(both))}, camera);
    const auto split =
        harness.render({shared(engine::test::make_cloud(red)), shared(engine::test::make_cloud(blue))}, camera);
    const auto d = engine::compare_images(merged, split);
    EXPECT_EQ(d.max_channel_difference, 0);
    // And the node transform applies: moving the second component changes the image.
    const auto moved =
        harness.render({shared(engine::test::make_cloud(red)), shared(engine::test::make_cloud(blue))}, camera,
                       glm::vec3(0.0f), {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0, 0))});
    EXPECT_GT(engine::compare_images(merged, moved).max_channel_difference, 50);
}

// docs/algorithms.md §7 hard cases through the GPU path: nothing crashes, nothing undefined is drawn,
// and the image agrees with the reference, which documents each case's behaviour.
TEST_F(SplatPipelineTest, HardCasesAgreeWithTheReference) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    std::vector<GaussianSpec> specs = {
        {{0.0f, 0.0f, 0.0f}, glm::vec3(-30.0f), {1, 0, 0, 0}, 3.0f, {1, 0, 0}},                 // scale ≈ 0
        {{0.3f, 0.0f, 0.0f}, glm::vec3(-1.5f, -15.0f, -15.0f), {1, 0, 0, 0}, 2.0f, {0, 1, 0}},  // anisotropy 1e6:1
        {{0.0f, 0.3f, 0.0f}, glm::vec3(-2.0f), {3, 1, 0, 0}, 2.0f, {0, 0, 1}},                  // non-unit quaternion
        {{0.0f, 0.0f, 0.0f}, glm::vec3(-2.0f), {0, 0, 0, 0}, 2.0f, {1, 1, 1}},                  // zero quaternion
        {{-0.3f, 0.0f, 0.0f}, glm::vec3(-2.0f), {1, 0, 0, 0}, 60.0f, {1, 1, 0}},                // logit +60
        {{-0.3f, 0.3f, 0.0f}, glm::vec3(-2.0f), {1, 0, 0, 0}, -60.0f, {1, 0, 1}},               // logit −60
        {{0.2f, -0.2f, 0.0f}, glm::vec3(-2.0f), {1, 0, 0, 0}, -5.6f, {0, 1, 1}},                // opacity < 1/255
        {{nan, 0.0f, 0.0f}, glm::vec3(-2.0f), {1, 0, 0, 0}, 2.0f, {1, 1, 1}},                   // NaN position
        {{0.0f, 0.0f, 0.0f}, glm::vec3(inf), {1, 0, 0, 0}, 2.0f, {1, 1, 1}},                    // Inf scale
        {{0.0f, 0.0f, 2.8f}, glm::vec3(-2.0f), {1, 0, 0, 0}, 2.0f, {1, 1, 1}},                  // at the near plane
        {{0.0f, 0.0f, 3.0f}, glm::vec3(-2.0f), {1, 0, 0, 0}, 2.0f, {1, 1, 1}},                  // on the camera centre
        {{0.0f, 0.0f, 5.0f}, glm::vec3(-2.0f), {1, 0, 0, 0}, 2.0f, {1, 1, 1}},                  // behind the camera
        {{1e6f, 0.0f, -1e6f}, glm::vec3(10.0f), {1, 0, 0, 0}, 2.0f, {0.5f, 0.5f, 0.5f}},        // far away, huge
        {{0.0f, -0.4f, -0.5f}, glm::vec3(12.0f), {1, 0, 0, 0}, -4.0f, {0.2f, 0.2f, 0.2f}},      // log-scale +12
    };
    for (int i = 0; i < 2000; ++i)
        specs.push_back(
            {{-0.2f, -0.2f, 0.0f}, glm::vec3(-3.0f), {1, 0, 0, 0}, 0.0f, {0.9f, 0.6f, 0.1f}});  // coincident
    for (int i = 0; i < 3; ++i)
        specs.push_back({{0.25f, 0.25f, 0.0f},
                         glm::vec3(-2.5f),
                         {1, 0, 0, 0},
                         0.5f,
                         {0.2f * i, 0.5f, 1.0f - 0.3f * i}});  // equal depths
    auto cloud_value = engine::test::make_cloud(specs);
    cloud_value.sh_dc[8] = glm::vec3(2.0f);
    const auto cloud = shared(std::move(cloud_value));
    const auto camera =
        engine::make_look_at_camera({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 128, 96, 0.1f, 1e7f);
    // The trained values as floats: the pipeline's own arithmetic against the double reference.
    splat_lod::SplatRenderer pass(harness.engine().renderer());
    pass.settings().gpu_storage = splat_lod::GpuStorage::full;
    const auto gpu = harness.render({cloud}, camera);
    expect_no_garbage(gpu);
    const auto again = harness.render({cloud}, camera);
    EXPECT_EQ(gpu.rgba, again.rgba) << "the same frame twice must be bit-identical";
    const auto d = engine::compare_images(gpu, reference(*cloud, camera));
    EXPECT_GE(d.psnr_db, 40.0);
    // The pass counts what it could not draw.
    ASSERT_TRUE(pass.latest_statistics().has_value());
    EXPECT_EQ(pass.latest_statistics()->considered, specs.size());

    // Compact storage draws what it stores, which the reference decodes: here a page whose box spans
    // the Gaussian at 10⁶ m and the coincident ones near the origin (steps of 15 m), so the stored
    // scene is not the trained one (docs/gpu_storage.md, "Pages"), but it is drawn without garbage,
    // deterministically and as the reference draws the same bytes.
    pass.settings().gpu_storage = splat_lod::GpuStorage::compact;
    const auto compact = harness.render({cloud}, camera);
    expect_no_garbage(compact);
    EXPECT_EQ(compact.rgba, harness.render({cloud}, camera).rgba);
    EXPECT_GE(engine::compare_images(compact, reference(splat_lod::compact_round_trip(*cloud, 0), camera)).psnr_db,
              40.0);
}

TEST_F(SplatPipelineTest, TinyHugeAndEmptyTargets) {
    const auto cloud =
        shared(engine::test::make_cloud({{{0, 0, 0}, glm::vec3(-1.0f), {1, 0, 0, 0}, 2.0f, {1, 0.5f, 0.2f}}}));
    for (const auto& [w, h] : {std::pair{1, 1}, std::pair{4096, 1}, std::pair{17, 33}}) {
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
        const auto camera =
            engine::make_look_at_camera({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), w, h, 0.1f, 100.0f);
        const auto gpu = harness.render({cloud}, camera);
        expect_no_garbage(gpu);
        EXPECT_LE(engine::compare_images(gpu, reference(*cloud, camera)).max_channel_difference, 2);
    }
    // An empty scene leaves the background.
    const auto camera =
        engine::make_look_at_camera({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 8, 8, 0.1f, 100.0f);
    const auto empty = harness.render({shared(splat_lod::SplatCloud{})}, camera, {0.2f, 0.4f, 0.6f});
    EXPECT_EQ(empty.pixel(3, 3)[1], 102);
}

// The frame's buffers start small and are sized by what the frame reads back after its scan: a first
// frame projecting more splats than the dense array holds runs steps 1–2 again with room, and no frame
// drops a pair. It draws what the next frame draws, and what the reference draws.
TEST_F(SplatPipelineTest, FirstFrameLargerThanItsBuffersDrawsEverything) {
    std::vector<GaussianSpec> specs;
    for (int i = 0; i < 6000; ++i)
        specs.push_back({{0.012f * (i % 100) - 0.6f, 0.02f * (i / 100) - 0.6f, -0.0001f * i},
                         glm::vec3(-4.0f),
                         {1, 0, 0, 0},
                         -1.0f,
                         {0.5f + 0.4f * std::sin(0.1f * i), 0.5f, 0.5f + 0.4f * std::cos(0.07f * i)}});
    const auto cloud = shared(engine::test::make_cloud(specs));
    const auto camera =
        engine::make_look_at_camera({0, 0, 2}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), 192, 192, 0.1f, 100.0f);
    engine::Scene scene;
    scene.background = glm::vec3(0.0f);
    auto component = std::make_unique<splat_lod::SplatComponent>();
    component->cloud = cloud;
    scene.root().add_child("s").attach(std::move(component));
    engine::RenderTarget target(camera.width, camera.height);
    auto& engine = harness.engine();
    splat_lod::SplatRenderer pass(engine.renderer());
    const auto first = splat_lod::render_complete(engine, scene, camera, target);
    const auto gpu = target.read_color();
    ASSERT_GT(first.visible, 4096u) << "more than the dense array's first capacity";
    EXPECT_EQ(pass.memory().selection_runs, 2u) << "steps 1-2 ran again with room";
    EXPECT_FALSE(first.overflowed);
    EXPECT_GE(pass.key_capacity(), first.tile_splat_pairs);
    EXPECT_LE(pass.memory().frame_bytes, 4u * (first.visible * 48u + first.tile_splat_pairs * 24u) + (1u << 20))
        << "sized by the frame, not by the scene";
    splat_lod::render_complete(engine, scene, camera, target);
    EXPECT_EQ(pass.memory().selection_runs, 1u);
    EXPECT_EQ(engine::compare_images(target.read_color(), gpu).max_channel_difference, 0)
        << "the next frame, with room";
    const auto cpu = reference(*cloud, camera);
    const auto d = engine::compare_images(gpu, cpu);
    if (d.psnr_db < 40.0) {
        const auto out = engine::test::output_dir("splat_pipeline");
        engine::write_png(out / "first_frame.gpu.png", gpu);
        engine::write_png(out / "first_frame.reference.png", cpu);
        engine::write_png(out / "first_frame.diff.png", d.visual);
    }
    EXPECT_GE(d.psnr_db, 40.0);
}

// Compositing by depth (docs/algorithms.md §1): a textured box in front of the biker's legs and a box
// behind him. The GPU frame equals the reference composited over the GPU mesh layer, and matches
// a golden image.
TEST_F(SplatPipelineTest, MeshesAndSplatsCompositeByDepth) {
    auto& engine = harness.engine();
    const auto scene_file = engine::test::repo_dir() / "content/scenes/biker_with_boxes.json";
    const auto full = engine.load_scene(scene_file);
    const int w = 192, h = 144;
    const auto camera = *engine::scene_camera(*full, "", w, h);

    engine::RenderTarget target(w, h);
    engine.renderer().render(*full, camera, target);
    splat_lod::SplatRenderer pass(engine.renderer());
    pass.wait_for_statistics(engine.bus());
    ASSERT_FALSE(pass.latest_statistics()->overflowed);
    const engine::Image gpu = target.read_color();

    // The mesh layer alone: the same scene without its splat node.
    auto meshes_only = engine.load_scene(scene_file);
    auto* biker = meshes_only->find_node("biker");
    auto* splat = biker->find_component<splat_lod::SplatComponent>();
    ASSERT_NE(splat, nullptr);
    const auto cloud = splat->cloud;
    const glm::mat4 model = biker->world_matrix();
    splat->cloud = std::make_shared<const splat_lod::SplatCloud>();
    engine.renderer().render(*meshes_only, camera, target);
    const engine::Image mesh_colour = target.read_color();
    const ref::MeshLayer layer = engine::test::mesh_layer(target);
    const ref::ReferenceInstance instance{cloud.get(), glm::dmat4(model), splat_lod::kMaxShDegree};
    const auto cpu =
        ref::to_image8(ref::render_reference(std::span(&instance, 1), camera, ref::ReferenceSettings{}, &layer));
    EXPECT_GE(engine::compare_images(gpu, cpu).psnr_db, 40.0);
    EXPECT_TRUE(engine::test::matches_golden(gpu, "splat_composite_biker_boxes"));
    // The front box hides splats: somewhere the composite equals the mesh layer exactly while the
    // splat-only reference there is not the background.
    EXPECT_GT(engine::compare_images(gpu, mesh_colour).fraction_over_threshold, 0.05);
}

// The GPU's selection (splat_project) against splat_lod::lod_selected on the CPU, for every
// mode of plugin_msgs::kLodModeNames: the same Gaussians per level are drawn, and the image equals the reference render
// of exactly the CPU-selected Gaussians. Coverage bounds are placed away from the decision thresholds so float and
// double cannot disagree.
TEST_F(SplatPipelineTest, LodSelectionMatchesTheCpuRule) {
    std::vector<GaussianSpec> specs;
    for (int i = 0; i < 400; ++i) {
        const float t = static_cast<float>(i);
        specs.push_back({{1.6f * std::sin(t * 1.3f), 1.2f * std::cos(t * 0.7f), -1.5f * std::sin(t * 0.23f)},
                         glm::vec3(-3.5f + 0.8f * std::sin(t * 0.5f)),
                         {1, 0, 0, 0},
                         1.5f,
                         {0.5f + 0.5f * std::sin(t), 0.4f, 0.5f + 0.5f * std::cos(t)}});
    }
    auto cloud = engine::test::make_cloud(specs);
    const auto camera =
        engine::make_look_at_camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 160, 120, 0.1f, 100.0f);
    const auto ref_camera = ref::make_reference_camera(camera);
    const ref::ReferenceSettings settings;
    std::vector<double> coverage(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto p = ref::project_gaussian(cloud, i, glm::dmat4(1.0), ref_camera, settings);
        const glm::dvec3 c = p.cov2d - glm::dvec3(settings.dilation, 0.0, settings.dilation);
        coverage[i] = splat_lod::pixel_coverage(c.x, c.y, c.z, p.opacity);
        cloud.lod_level[i] = static_cast<std::uint8_t>(1 + i % 4);
        // Ranges a factor 3 or 1/3 away from this view's coverage, or unset: far from any threshold.
        const double f = (i % 3 == 0) ? 3.0 : (i % 3 == 1 ? 1.0 / 3.0 : 1.0);
        cloud.coverage_min[i] = (i % 5 == 0) ? -1.0f : static_cast<float>(coverage[i] * f);
        cloud.coverage_max[i] = (i % 7 == 0) ? -1.0f : static_cast<float>(coverage[i] / f);
    }
    const auto shared_cloud = shared(cloud);
    splat_lod::SplatRenderer pass(harness.engine().renderer());
    std::map<plugin_msgs::LodMode, std::array<std::uint64_t, 4>> counts;
    for (std::size_t m = 0; m < plugin_msgs::kLodModeNames.size(); ++m) {  // every mode, a new one included
        const auto mode = static_cast<plugin_msgs::LodMode>(m);
        SCOPED_TRACE(std::string(plugin_msgs::to_string(mode)));
        plugin_msgs::LodSettings lod;
        lod.rule.mode = mode;
        lod.rule.transition_band = 0.0f;      // hard switching: the rule itself
        harness.engine().bus().publish(lod);  // the plugin takes settings from the bus
        ASSERT_EQ(pass.lod().rule.mode, mode);
        const splat_lod::LodRule rule = pass.lod().rule;
        std::vector<std::uint8_t> keep(cloud.size());
        std::array<std::uint64_t, 4> per_level{0, 0, 0, 0};
        for (std::size_t i = 0; i < cloud.size(); ++i) {
            const bool drawn = ref::project_gaussian(cloud, i, glm::dmat4(1.0), ref_camera, settings).drawn();
            keep[i] = drawn && splat_lod::lod_selected(rule, cloud.lod_level[i], coverage[i], cloud.coverage_min[i],
                                                       cloud.coverage_max[i]);
            if (keep[i]) ++per_level[cloud.lod_level[i] - 1u];
        }
        const auto gpu = harness.render({shared_cloud}, camera);
        EXPECT_EQ(pass.latest_statistics()->per_level, per_level);
        counts[mode] = per_level;
        auto selected = cloud;
        selected.keep_only(keep);
        EXPECT_GE(engine::compare_images(gpu, reference(selected, camera)).psnr_db, 40.0);
    }
    // The case is not vacuous: the modes select different sets.
    using M = plugin_msgs::LodMode;
    EXPECT_EQ(counts[M::baseline][1] + counts[M::baseline][2] + counts[M::baseline][3], 0u);
    EXPECT_LT(counts[M::filter_small][0], counts[M::baseline][0]);
    for (int l = 0; l < 4; ++l) EXPECT_GT(counts[M::insert_large][static_cast<std::size_t>(l)], 0u);
    for (int l = 1; l < 4; ++l)
        EXPECT_LT(counts[M::full][static_cast<std::size_t>(l)], counts[M::insert_large][static_cast<std::size_t>(l)]);
}

TEST_F(SplatPipelineTest, LevelColouringTintsEachLevel) {
    auto cloud = engine::test::make_cloud({{{-0.6f, 0, 0}, glm::vec3(-1.5f), {1, 0, 0, 0}, 4.0f, {0.9f, 0.9f, 0.9f}},
                                           {{0.6f, 0, 0}, glm::vec3(-1.5f), {1, 0, 0, 0}, 4.0f, {0.9f, 0.9f, 0.9f}}});
    cloud.lod_level[1] = 2;
    plugin_msgs::LodSettings lod;
    lod.rule.mode = plugin_msgs::LodMode::insert_large;
    lod.level_colouring = true;
    harness.engine().bus().publish(lod);
    const auto camera =
        engine::make_look_at_camera({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 96, 48, 0.1f, 100.0f);
    const auto image = harness.render({shared(cloud)}, camera);
    // f = 24 / tan(25°) = 51.5 px, so x = ±0.6 at distance 3 lands 10 px either side of the centre.
    const auto* grey = image.pixel(48 - 10, 24);   // level 1
    const auto* green = image.pixel(48 + 10, 24);  // level 2
    EXPECT_NEAR(int(grey[0]), int(grey[1]), 2);
    EXPECT_GT(int(grey[0]), 100);
    EXPECT_GT(int(green[1]), int(green[0]) + 60);
    EXPECT_GT(int(green[1]), int(green[2]) + 60);
}

// SplatComponent::dissolve (the streamer's fades): at opacity f a component draws about the fraction f of
// its Gaussians, each at full opacity, the same subset every frame; two components cross-fading at f and
// 1 − f draw about as many Gaussians as one of them. Without dissolve every Gaussian is drawn fainter.
TEST_F(SplatPipelineTest, DissolveDrawsAFractionOfTheGaussians) {
    std::vector<GaussianSpec> specs;
    for (int i = 0; i < 2000; ++i) {
        const float t = static_cast<float>(i);
        specs.push_back({{1.6f * std::sin(t * 1.3f), 1.2f * std::cos(t * 0.7f), -1.5f * std::sin(t * 0.23f)},
                         glm::vec3(-3.0f),
                         {1, 0, 0, 0},
                         2.0f,
                         {0.5f + 0.5f * std::sin(t), 0.4f, 0.5f + 0.5f * std::cos(t)}});
    }
    // Two copies, as a streamed node and its replacement are two clouds.
    const std::array clouds{shared(engine::test::make_cloud(specs)), shared(engine::test::make_cloud(specs))};
    const auto camera =
        engine::make_look_at_camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 160, 120, 0.1f, 100.0f);
    auto& engine = harness.engine();
    splat_lod::SplatRenderer pass(engine.renderer());
    engine::RenderTarget target(160, 120);
    // Draws one or two components of the cloud with these opacities; returns the visible count and image.
    const auto draw = [&](std::vector<float> opacities, bool dissolve) {
        engine::Scene scene;
        for (std::size_t i = 0; i < opacities.size(); ++i) {
            auto component = std::make_unique<splat_lod::SplatComponent>();
            component->cloud = clouds[i % clouds.size()];
            component->opacity = opacities[i];
            component->dissolve = dissolve;
            scene.root().add_child("s" + std::to_string(i)).attach(std::move(component));
        }
        engine.renderer().render(scene, camera, target);
        pass.wait_for_statistics(engine.bus());
        return std::pair{pass.latest_statistics()->visible, target.read_color()};
    };
    const auto [all, whole] = draw({1.0f}, true);
    ASSERT_GT(all, 1500u) << "most of the cloud is in view";
    EXPECT_EQ(draw({1.0f}, false).second.rgba, whole.rgba) << "at opacity 1 dissolve changes nothing";
    for (const float f : {0.25f, 0.5f, 0.75f}) {
        SCOPED_TRACE("opacity " + std::to_string(f));
        const auto [part, image] = draw({f}, true);
        EXPECT_NEAR(static_cast<double>(part), f * static_cast<double>(all), 0.06 * static_cast<double>(all));
        EXPECT_EQ(draw({f}, true).second.rgba, image.rgba) << "the same subset every frame";
        EXPECT_EQ(draw({f}, false).first, all) << "without dissolve every Gaussian is drawn, fainter";
        const auto [both, crossfade] = draw({f, 1.0f - f}, true);
        EXPECT_NEAR(static_cast<double>(both), static_cast<double>(all), 0.08 * static_cast<double>(all))
            << "a cross-fade draws about one side's count, not two";
    }
    EXPECT_EQ(draw({0.0f}, true).first, 0u);
}
