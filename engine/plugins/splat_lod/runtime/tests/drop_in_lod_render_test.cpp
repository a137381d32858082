// The drop-in LOD in frames ("lod": "auto", docs/lod.md): the first frame draws the trained scene, the
// plugin swaps the finished bake in at the start of a later frame, and that frame draws the levels.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "drop_in_lod_test_helpers.h"
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
    ASSERT_NE(splat.lod_bake, nullptr);
    const auto job = splat.lod_bake;  // kept to read the result after the swap
    release = true;
    ASSERT_TRUE(job->wait(120.0));
    ASSERT_EQ(job->state(), splat_lod::bake::BackgroundBake::State::done) << job->error();

    // The next frame swaps it in before anything is drawn.
    const auto after = splat_lod::render_complete(*engine, *scene, camera, target);
    EXPECT_EQ(splat.lod_bake, nullptr);
    EXPECT_EQ(splat.cloud, job->result());
    EXPECT_EQ(after.considered, job->result()->size());
    EXPECT_GT(drawn_pixels(target.read_color()), 500u);
}

}  // namespace
