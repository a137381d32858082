// A generated world streamed through the real splat pass: ChunkStreamer → SceneResidencySink →
// scene nodes → the incremental GpuScene. What the streamer counts is what the GPU holds and
// uploads, frame by frame, along a camera path.
#include <cmath>

#include "engine/engine.h"
#include "engine/render/render_target.h"
#include "engine/scene/scene.h"
#include "gpu_fixture.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "splat_lod/stream/chunk_streamer.h"
#include "splat_lod/stream/stream_scene_sink.h"
#include "splat_lod/worldgen/world_generator.h"
#include "splat_test_scenes.h"
#include "test_support.h"
#include "tiny_world.h"

namespace sw = splat_lod::world;

namespace {

class SplatStreamingTest : public engine::test::GpuTest {};

// The tests' tiny world (tiny_world.h) without its terrain mesh: only splats are drawn here.
sw::WorldResult tiny_world(const std::filesystem::path& folder) {
    sw::WorldOptions o = engine::test::tiny_world_options(folder);
    o.terrain_mesh = false;
    return sw::generate_world(o);
}

}  // namespace

TEST_F(SplatStreamingTest, WhatTheStreamerCountsIsWhatTheGpuHolds) {
    const auto folder = engine::test::output_dir("splat_streaming") / "world";
    const sw::WorldResult world = tiny_world(folder);
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    splat_lod::SplatRenderer pass(engine.renderer());
    engine::Scene scene;
    engine::Node& root = scene.root().add_child("world");
    sw::SceneResidencySink sink(root);
    sw::FileChunkSource source;
    sw::StreamerSettings settings;
    settings.background_thread = false;
    settings.gpu_sh_degree = 0;  // what the generated chunks carry: the GPU stride is degree 0's
    const std::uint64_t page = sw::gpu_bytes(1, 0, settings.gpu_pages);
    settings.upload_budget_bytes_per_frame = 4 * page;
    settings.memory_budget_bytes = 40 * page;
    settings.unload_delay_frames = 0;
    sw::ChunkStreamer streamer(world.manifest, folder, settings, source, sink, &engine.bus());

    const int w = 160, h = 120;
    engine::RenderTarget target(w, h);
    std::uint64_t peak_resident = 0;
    int frames_with_uploads = 0;
    // From the world's far corner, high up, down to the ground in the middle and back out.
    for (int frame = 0; frame < 60; ++frame) {
        const float t = static_cast<float>(frame) / 59.0f;
        const float s = 1.0f - std::abs(2.0f * t - 1.0f);  // 0 → 1 → 0
        const glm::vec3 eye = glm::mix(glm::vec3(140.0f, 120.0f, 140.0f), glm::vec3(2.0f, 3.0f, 2.0f), s);
        const auto camera =
            engine::make_look_at_camera(eye, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, glm::radians(60.0f), w, h, 0.1f, 2000.0f);
        streamer.update({eye, camera.focal_length(), static_cast<std::uint64_t>(frame)});
        engine.renderer().render(scene, camera, target);
        const splat_lod::SplatMemory gpu = pass.memory();
        SCOPED_TRACE("frame " + std::to_string(frame));
        // The GPU uploaded within the streamer's per-frame budget (clusters of freed pages aside,
        // one GpuCluster each), and holds exactly the pages the streamer counts as resident.
        EXPECT_LE(gpu.last_upload_bytes,
                  settings.upload_budget_bytes_per_frame + sizeof(splat_lod::gpu::GpuCluster) * 64u);
        EXPECT_EQ(std::uint64_t(gpu.pages_in_use) * gpu.page_bytes, streamer.resident_bytes());
        EXPECT_LE(streamer.resident_bytes(), settings.memory_budget_bytes);
        EXPECT_EQ(sink.resident_parts(), root.children().size());
        peak_resident = std::max(peak_resident, streamer.resident_bytes());
        frames_with_uploads += gpu.last_upload_bytes > 0 ? 1 : 0;
    }
    EXPECT_GT(frames_with_uploads, 5) << "the upload budget spread the world over frames";
    EXPECT_GT(peak_resident, 9 * page) << "more than the coarsest level of each chunk became resident";
    pass.wait_for_statistics(engine.bus());
    const auto image = target.read_color();
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) ASSERT_EQ(image.rgba[i], 255);
    engine::write_png(engine::test::output_dir("splat_streaming") / "last_frame.png", image);
    streamer.release_all();
    engine.renderer().render(
        scene, engine::make_look_at_camera({0, 50, 50}, {0, 0, 0}, {0, 1, 0}, 1.0f, w, h, 0.1f, 2000.0f), target);
    EXPECT_EQ(pass.memory().pages_in_use, 0u);
}

TEST_F(SplatStreamingTest, AHiddenComponentStaysResidentAndIsNotDrawn) {
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    splat_lod::SplatRenderer pass(engine.renderer());
    engine::Scene scene;
    scene.background = {0.2f, 0.3f, 0.4f};
    auto component = std::make_unique<splat_lod::SplatComponent>();
    engine::test::GaussianSpec a, b;
    a.log_scale = glm::vec3(-1.5f);
    a.color = {1.0f, 0.2f, 0.1f};
    b.position = {0.4f, 0.2f, 0.0f};
    b.color = {0.1f, 0.9f, 0.3f};
    component->cloud = std::make_shared<const splat_lod::SplatCloud>(engine::test::make_cloud({a, b}));
    splat_lod::SplatComponent& splats = scene.root().add_child("splats").add_component(std::move(component));
    const int w = 64, h = 48;
    const auto camera =
        engine::make_look_at_camera({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), w, h, 0.1f, 100.0f);
    engine::RenderTarget target(w, h);
    const auto draw = [&] {
        engine.renderer().render(scene, camera, target);
        pass.wait_for_statistics(engine.bus());
        return target.read_color().rgba;
    };
    const auto shown = draw();
    EXPECT_EQ(pass.latest_statistics()->visible, 2u);
    const std::uint32_t pages = pass.memory().pages_in_use;

    splats.visible = false;
    const auto hidden = draw();
    EXPECT_EQ(pass.memory().pages_in_use, pages) << "still resident";
    EXPECT_EQ(pass.memory().last_upload_bytes, 0u) << "hiding uploads nothing";
    EXPECT_EQ(pass.latest_statistics()->visible, 0u);
    EXPECT_EQ(pass.latest_statistics()->culled, 0u) << "hidden Gaussians are not counted as culled";
    // Counted by whole clusters (pages of 256 slots, the last one padded), as culled Gaussians are.
    EXPECT_GE(pass.latest_statistics()->hidden, 2u);
    EXPECT_LE(pass.latest_statistics()->hidden, 256u);
    for (std::size_t i = 0; i < hidden.size(); i += 4) {
        ASSERT_EQ(hidden[i], 51) << "pixel " << i / 4;  // the background, 0.2 · 255
        ASSERT_EQ(hidden[i + 2], 102) << "pixel " << i / 4;
    }
    EXPECT_NE(shown, hidden);

    splats.visible = true;
    EXPECT_EQ(draw(), shown);
    EXPECT_EQ(pass.memory().last_upload_bytes, 0u);
}
