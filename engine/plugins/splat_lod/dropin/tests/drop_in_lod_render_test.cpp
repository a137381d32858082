// The drop-in LOD in frames ("lod": "auto", docs/lod.md): the first frame draws the trained scene, the
// plugin swaps the finished bake in at the start of a later frame, and that frame draws the levels; a
// capture imported as a world takes over the same way and draws like the capture.
#include <gtest/gtest.h>

#include <atomic>
#include <iostream>
#include <thread>

#include "drop_in_lod_test_helpers.h"
#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "engine/render/render_target.h"
#include "gpu_fixture.h"
#include "splat_lod/bake/lod_cache.h"

namespace {

using namespace drop_in_lod_test;

class DropInLodRender : public engine::test::GpuTest {};

// Pixels that are not the background (black).
std::size_t drawn_pixels(const engine::Image& image) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4)
        n += image.rgba[i] + image.rgba[i + 1] + image.rgba[i + 2] > 6;
    return n;
}

TEST_F(DropInLodRender, FramesDrawTheTrainedSceneThenTheBakedLevels) {
    const fs::path dir = engine::test::output_dir("DropInLodRender");
    fs::remove_all(dir);
    std::atomic<bool> release{false};
    auto settings = quick_settings();
    settings.cache_folder = dir / "cache";
    settings.observer = [&](const std::string&, double) {
        while (!release) std::this_thread::yield();  // held until the first frame was drawn
    };
    auto engine = make_engine(settings);
    auto scene = engine->load_scene(write_scene(dir, R"(, "lod": "auto")"));
    const ReleaseOnExit guard{release};
    scene->background = glm::vec3(0.0f);
    auto& splat = splat_of(*scene);
    const auto trained = splat.cloud;
    const int w = 160, h = 120;
    const auto camera = engine::test::orbit_cameras(*trained, glm::vec3(0, 1, 0), 1, w, h)[0];
    engine::RenderTarget target(w, h);

    const auto first = splat_lod::render_complete(*engine, *scene, camera, target);
    EXPECT_EQ(first.considered, trained->size());
    EXPECT_GT(drawn_pixels(target.read_color()), 500u);
    ASSERT_NE(splat_lod::dropin::background_bake(splat), nullptr);
    const auto job = splat_lod::dropin::background_bake(splat);  // kept to read the result after the swap
    release = true;
    ASSERT_TRUE(job->wait(120.0));
    ASSERT_EQ(job->state(), splat_lod::bake::BackgroundBake::State::done) << job->error();

    // The next frame swaps it in before anything is drawn.
    const auto after = splat_lod::render_complete(*engine, *scene, camera, target);
    EXPECT_EQ(splat_lod::dropin::background_bake(splat), nullptr);
    EXPECT_EQ(splat.cloud, job->result());
    EXPECT_EQ(after.considered, job->result()->size());
    EXPECT_GT(drawn_pixels(target.read_color()), 500u);
}

// The streamed world in frames: the first frames draw the trained capture, later ones the world that the
// import made of it, placed where the capture was and streamed for the frame's camera, and it looks like
// the capture from that camera.
TEST_F(DropInLodRender, AStreamedWorldTakesOverFromTheTrainedCaptureAndLooksLikeIt) {
    const fs::path dir = engine::test::output_dir("DropInLodRender");
    fs::remove_all(dir);
    std::atomic<bool> release{false};
    auto settings = world_settings(dir / "cache");
    settings.observer = [&](const std::string&, double) {
        while (!release) std::this_thread::yield();  // held until the first frame was drawn
    };
    auto engine = make_engine(settings);
    auto scene = engine->load_scene(write_capture_scene(dir));
    const ReleaseOnExit guard{release};
    scene->background = glm::vec3(0.0f);
    auto& splat = splat_of(*scene);
    const auto trained = splat.cloud;
    const int w = 160, h = 120;
    const auto camera = engine::make_look_at_camera({6.0f, -14.0f, 18.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, -1.0f, 0.0f},
                                                    glm::radians(60.0f), w, h, 0.1f, 200.0f);
    engine::RenderTarget target(w, h);
    const auto first = splat_lod::render_complete(*engine, *scene, camera, target);
    EXPECT_EQ(first.considered, trained->size());
    const engine::Image trained_image = target.read_color();
    EXPECT_GT(drawn_pixels(trained_image), 5000u);
    release = true;
    ASSERT_TRUE(splat_lod::dropin::wait_for_import(splat, 300.0));
    int frames = 0;
    while (splat.cloud && frames < 400) {
        splat_lod::render_complete(*engine, *scene, camera, target);
        ++frames;
    }
    ASSERT_EQ(splat.cloud, nullptr) << "the world still held after " << frames << " frames";
    for (int i = 0; i < 8; ++i) splat_lod::render_complete(*engine, *scene, camera, target);  // fades end
    const engine::Image world_image = target.read_color();
    engine::write_png(dir / "trained.png", trained_image);
    engine::write_png(dir / "streamed.png", world_image);
    const engine::ImageDifference difference = engine::compare_images(trained_image, world_image);
    std::cout << "streamed world against the trained capture: " << difference.psnr_db << " dB after " << frames
              << " frames\n";
    EXPECT_GE(difference.psnr_db, 30.0);
}

}  // namespace
