// "lod": "auto" on a capture better served as a streamed world (drop_in_lod.h), without GL: the import in
// the background while the trained scene is drawn, the world streamed under the component's node and
// placed where the capture was, the trained scene released once the cut is drawn, the next load finding
// the import done, and a failed or cancelled import leaving the trained scene and no world. Also what
// "lod": "auto" does when the program has no drop-in LOD.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

#include "drop_in_lod_test_helpers.h"
#include "engine/core/error.h"
#include "engine/scene/node.h"
#include "splat_lod/core/world_manifest.h"

namespace {

using namespace drop_in_lod_test;
using splat_lod::SplatCloud;
using splat_lod::SplatComponent;
using splat_lod::dropin::WorldStatus;

// Frames from a camera 12 units above the capture's ground (the capture's frame is Y-down: "above" is −y),
// until the trained scene is released or `frames` have passed; returns the frames it took.
int stream_until_released(SplatComponent& splat, int frames) {
    splat_lod::LodFrame frame;
    frame.camera_position = {0.0f, -12.0f, 0.0f};
    frame.focal_length_px = 300.0f;
    for (int i = 1; i <= frames; ++i) {
        frame.frame_index = static_cast<std::uint64_t>(i);
        splat.update_lod(frame);
        if (!splat.cloud) return i;
    }
    return frames + 1;
}

// The splat components under `node` that are drawn, and their Gaussians.
std::size_t drawn_gaussians(const engine::Node& node) {
    std::size_t n = 0;
    node.visit([&](const engine::Node& child) {
        for (const auto& c : child.components())
            if (const auto* s = dynamic_cast<const SplatComponent*>(c.get()); s && s->visible && s->cloud)
                n += s->cloud->size();
    });
    return n;
}

const engine::Node* child_named(const engine::Node& node, const std::string& name) {
    for (const auto& child : node.children())
        if (child->name() == name) return child.get();
    return nullptr;
}

TEST(DropInWorld, ACaptureIsImportedThenStreamedWhereItWasAndTheNextLoadStreamsAtOnce) {
    const fs::path dir = engine::test::output_dir("DropInWorld");
    fs::remove_all(dir);
    const fs::path scene_file = write_capture_scene(dir);
    std::atomic<int> chunk_reports{0};
    auto settings = world_settings(dir / "cache");
    settings.observer = [&](const std::string& stage, double) { chunk_reports += stage == "import: chunks"; };
    {
        auto engine = make_engine(settings);
        auto scene = engine->load_scene(scene_file);
        auto& splat = splat_of(*scene);
        const auto trained = splat.cloud;
        ASSERT_NE(trained, nullptr);
        EXPECT_EQ(splat_lod::dropin::background_bake(splat), nullptr) << "no bake of one file";
        EXPECT_EQ(splat_lod::dropin::world_status(splat).state, WorldStatus::State::importing);
        ASSERT_TRUE(splat_lod::dropin::wait_for_import(splat, 300.0));
        const int frames = stream_until_released(splat, 400);
        const WorldStatus status = splat_lod::dropin::world_status(splat);
        ASSERT_EQ(status.state, WorldStatus::State::streaming) << "after " << frames << " frames";
        EXPECT_EQ(status.folder, splat_lod::dropin::world_cache_folder(dir / "cache", dir / "capture.ply"));
        EXPECT_TRUE(fs::exists(status.folder / splat_lod::world::kManifestFileName));
        EXPECT_GT(status.streamer->chunk_count(), 4u);
        EXPECT_EQ(splat.cloud, nullptr) << "the trained scene is released once the cut is drawn";
        const engine::Node* world = child_named(*splat.node(), "streamed world");
        ASSERT_NE(world, nullptr);
        EXPECT_GT(drawn_gaussians(*world), 1000u);
        // The far layer (the sky Gaussians and the ground's outermost edge) lands where the capture had it:
        // the import's map, undone.
        const engine::Node* far = child_named(*world, "far_layer 0");
        ASSERT_NE(far, nullptr);
        const auto* layer = far->find_component<SplatComponent>();
        ASSERT_NE(layer, nullptr);
        ASSERT_GE(layer->cloud->size(), 3u);
        const glm::mat4 to_scene = far->world_matrix();
        std::size_t sky = 0;
        for (std::size_t i = 0; i < layer->cloud->size(); ++i) {
            const glm::vec3 p = glm::vec3(to_scene * glm::vec4(layer->cloud->positions[i], 1.0f));
            float nearest = 1e9f;
            for (const glm::vec3& q : trained->positions) nearest = std::min(nearest, glm::distance(p, q));
            EXPECT_LT(nearest, 1e-3f) << "far layer Gaussian " << i << " at " << p.x << ", " << p.y << ", " << p.z;
            sky += p.y < -20.0f;  // the capture is Y-down: the sky is at y = −25
        }
        EXPECT_EQ(sky, 3u);
        EXPECT_GT(chunk_reports.load(), 0);
    }
    // A fresh engine: the import is found done (no chunk baked again) and the world streams.
    chunk_reports = 0;
    auto engine = make_engine(settings);
    auto scene = engine->load_scene(scene_file);
    auto& splat = splat_of(*scene);
    ASSERT_TRUE(splat_lod::dropin::wait_for_import(splat, 60.0));
    stream_until_released(splat, 400);
    EXPECT_EQ(splat_lod::dropin::world_status(splat).state, WorldStatus::State::streaming);
    EXPECT_EQ(chunk_reports.load(), 0) << "the cached world is not imported again";
}

TEST(DropInWorld, AFailedImportKeepsTheTrainedSceneAndLeavesNoWorld) {
    const fs::path dir = engine::test::output_dir("DropInWorld");
    fs::remove_all(dir);
    auto settings = world_settings(dir / "cache");
    settings.observer = [](const std::string& stage, double) {
        if (stage == "import: chunks") engine::fail("forced failure");
    };
    auto engine = make_engine(settings);
    auto scene = engine->load_scene(write_capture_scene(dir));
    auto& splat = splat_of(*scene);
    const auto trained = splat.cloud;
    const fs::path folder = splat_lod::dropin::world_status(splat).folder;
    ASSERT_TRUE(splat_lod::dropin::wait_for_import(splat, 300.0));
    EXPECT_FALSE(splat.update_lod({}));
    EXPECT_EQ(splat.lod_job, nullptr) << "nothing left to do";
    EXPECT_EQ(splat.cloud, trained) << "the trained scene keeps drawing";
    EXPECT_FALSE(fs::exists(folder / splat_lod::world::kManifestFileName));
}

TEST(DropInWorld, ClosingTheSceneCancelsTheImport) {
    const fs::path dir = engine::test::output_dir("DropInWorld");
    fs::remove_all(dir);
    std::atomic<bool> midway{false}, release{false};
    auto settings = world_settings(dir / "cache");
    settings.observer = [&](const std::string& stage, double) {
        if (stage != "import: chunks") return;
        midway = true;
        while (!release) std::this_thread::yield();  // held until the test closes the scene
    };
    auto engine = make_engine(settings);
    fs::path folder;
    {
        auto scene = engine->load_scene(write_capture_scene(dir));
        const ReleaseOnExit guard{release};
        folder = splat_lod::dropin::world_status(splat_of(*scene)).folder;
        while (!midway) std::this_thread::yield();
        release = true;
        scene.reset();  // cancels the import at its next report and waits for it
    }
    EXPECT_FALSE(fs::exists(folder / splat_lod::world::kManifestFileName));
}

TEST(DropInWorld, EachCaptureHasItsOwnFolderNamedAfterIt) {
    using splat_lod::dropin::world_cache_folder;
    const fs::path park = world_cache_folder("/cache", "/data/park/lod-meta.json");
    EXPECT_EQ(park.parent_path(), fs::path("/cache/worlds"));
    EXPECT_EQ(park.filename().string().rfind("park-", 0), 0u) << park << ": a streamed SOG is named by its folder";
    EXPECT_EQ(world_cache_folder("/cache", "/data/site.ply").filename().string().rfind("site-", 0), 0u);
    EXPECT_NE(world_cache_folder("/cache", "/data/a/site.ply"), world_cache_folder("/cache", "/data/b/site.ply"));
    EXPECT_EQ(world_cache_folder("/cache", "/data/./a/site.ply"), world_cache_folder("/cache", "/data/a/site.ply"));
}

TEST(DropInWorld, WithoutTheDropInLodAutoDrawsTheFileAsItIs) {
    const fs::path dir = engine::test::output_dir("DropInWorld");
    fs::remove_all(dir);
    auto engine = std::make_unique<engine::Engine>();
    engine->plugins().add_static(splat_lod::make_plugin());
    auto scene = engine->load_scene(write_capture_scene(dir));
    auto& splat = splat_of(*scene);
    ASSERT_NE(splat.cloud, nullptr);
    EXPECT_EQ(splat.lod_job, nullptr);
    EXPECT_FALSE(splat.cloud->has_lod_attributes());
}

}  // namespace
