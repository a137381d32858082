// The splat component's drop-in LOD ("lod": "auto", docs/lod.md) without GL: the trained scene first,
// the background bake, the swap, the cache hit of the next load, and what failed, cancelled and bad
// values leave behind. The frames before and after the swap: drop_in_lod_render_test.cpp.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "drop_in_lod_test_helpers.h"
#include "engine/core/error.h"
#include "splat_lod/bake/capture_shape.h"
#include "splat_lod/bake/lod_cache.h"

namespace {

using namespace drop_in_lod_test;
using splat_lod::bake::BackgroundBake;

// The cache folder under the test's own XDG_CACHE_HOME.
fs::path lod_folder(const fs::path& xdg) {
    return xdg / "splat_engine" / "lod";
}

TEST(DropInLod, FirstLoadDrawsTheTrainedSceneThenTheBakeAndTheNextLoadHitsTheCache) {
    const fs::path dir = engine::test::output_dir("DropInLod");
    fs::remove_all(dir);
    const ScopedEnv xdg("XDG_CACHE_HOME", (dir / "xdg").string());
    const fs::path scene_file = write_scene(dir, R"(, "lod": "auto")");
    const auto trained = splat_lod::load_splat_file(dir / "scene.ply");
    std::shared_ptr<const splat_lod::SplatCloud> baked;
    {
        std::atomic<bool> release{false};
        auto settings = quick_settings();
        settings.observer = [&](const std::string&, double) {
            while (!release) std::this_thread::yield();  // held until the trained scene was checked
        };
        auto engine = make_engine(settings);
        auto scene = engine->load_scene(scene_file);
        const ReleaseOnExit guard{release};
        auto& splat = splat_of(*scene);
        // At once: the trained scene, as without "lod"; the bake runs beside it.
        ASSERT_NE(splat.cloud, nullptr);
        EXPECT_FALSE(splat.cloud->has_lod_attributes());
        EXPECT_EQ(splat.cloud->size(), trained.size());
        const auto job = splat_lod::dropin::background_bake(splat);
        ASSERT_NE(job, nullptr);
        EXPECT_FALSE(splat.update_lod()) << "a running bake keeps the trained scene";
        EXPECT_EQ(splat_lod::dropin::background_bake(splat), job);
        release = true;
        ASSERT_TRUE(job->wait(120.0));
        ASSERT_EQ(job->state(), BackgroundBake::State::done) << job->error();
        EXPECT_TRUE(splat.update_lod());
        EXPECT_EQ(splat_lod::dropin::background_bake(splat), nullptr);
        baked = splat.cloud;
        EXPECT_TRUE(baked->has_lod_attributes());
        EXPECT_GT(baked->size(), trained.size());
        EXPECT_GT(*std::max_element(baked->lod_level.begin(), baked->lod_level.end()), 1);
    }
    // One complete entry, named by the key, and nothing else.
    const auto names = entries(lod_folder(dir / "xdg"));
    ASSERT_EQ(names.size(), 1u);
    EXPECT_EQ(names[0].size(), std::string("0123456789abcdef-01234567.lod.ply").size()) << names[0];
    // The next load (a fresh engine: nothing in memory) takes the asset from the cache at once.
    auto engine = make_engine();
    auto scene = engine->load_scene(scene_file);
    auto& splat = splat_of(*scene);
    EXPECT_EQ(splat_lod::dropin::background_bake(splat), nullptr) << "no bake on a cache hit";
    ASSERT_TRUE(splat.cloud->has_lod_attributes());
    EXPECT_EQ(splat.cloud->size(), baked->size());
    EXPECT_EQ(splat.cloud->lod_level, baked->lod_level);
    // Other settings are another key: a bake again.
    auto settings = quick_settings();
    settings.setup.options.refine_iterations = 21;
    auto other_engine = make_engine(settings);
    auto other = other_engine->load_scene(scene_file);
    EXPECT_NE(splat_lod::dropin::background_bake(splat_of(*other)), nullptr);
}

TEST(DropInLod, TheRealAdviceKeepsASmallSceneBaking) {
    const fs::path dir = engine::test::output_dir("DropInLod");
    fs::remove_all(dir);
    auto settings = quick_settings();
    settings.cache_folder = dir / "cache";
    auto engine = make_engine(settings);
    auto scene = engine->load_scene(write_scene(dir, R"(, "lod": "auto")"));
    auto& splat = splat_of(*scene);
    EXPECT_EQ(splat_lod::bake::streamed_world_advice(*splat.cloud), "");
    EXPECT_NE(splat_lod::dropin::background_bake(splat), nullptr);
    EXPECT_EQ(splat_lod::dropin::world_status(splat).state, splat_lod::dropin::WorldStatus::State::none);
}

TEST(DropInLod, FailedBakeKeepsTheTrainedSceneAndCachesNothing) {
    const fs::path dir = engine::test::output_dir("DropInLod");
    fs::remove_all(dir);
    const fs::path cache = dir / "cache";
    auto settings = quick_settings();
    settings.cache_folder = cache;  // the setting instead of XDG_CACHE_HOME
    settings.observer = [](const std::string& stage, double) {
        if (stage.find("refine level") != std::string::npos) engine::fail("forced failure");
    };
    auto engine = make_engine(settings);
    auto scene = engine->load_scene(write_scene(dir, R"(, "lod": "auto")"));
    auto& splat = splat_of(*scene);
    const auto trained = splat.cloud;
    ASSERT_NE(splat_lod::dropin::background_bake(splat), nullptr);
    ASSERT_TRUE(splat_lod::dropin::background_bake(splat)->wait(60.0));
    EXPECT_EQ(splat_lod::dropin::background_bake(splat)->state(), BackgroundBake::State::failed);
    EXPECT_EQ(splat_lod::dropin::background_bake(splat)->error(), "scene.ply: forced failure");
    EXPECT_FALSE(splat.update_lod());
    EXPECT_EQ(splat_lod::dropin::background_bake(splat), nullptr);
    EXPECT_EQ(splat.cloud, trained) << "the trained scene keeps drawing";
    EXPECT_TRUE(entries(cache).empty());
}

TEST(DropInLod, BakeCancelledMidwayOrByClosingTheSceneCachesNothing) {
    const fs::path dir = engine::test::output_dir("DropInLod");
    fs::remove_all(dir);
    const fs::path cache = dir / "cache";
    std::atomic<bool> midway{false}, release{false};
    auto settings = quick_settings();
    settings.cache_folder = cache;
    settings.observer = [&](const std::string& stage, double) {
        if (stage.find("refine level") == std::string::npos) return;
        midway = true;
        while (!release) std::this_thread::yield();  // held midway until the test has cancelled
    };
    auto engine = make_engine(settings);
    const fs::path scene_file = write_scene(dir, R"(, "lod": "auto")");
    {
        auto scene = engine->load_scene(scene_file);
        const ReleaseOnExit guard{release};
        auto& splat = splat_of(*scene);
        ASSERT_NE(splat_lod::dropin::background_bake(splat), nullptr);
        while (!midway && splat_lod::dropin::background_bake(splat)->state() == BackgroundBake::State::running)
            std::this_thread::yield();
        ASSERT_TRUE(midway.load());
        splat_lod::dropin::background_bake(splat)->cancel();
        release = true;
        ASSERT_TRUE(splat_lod::dropin::background_bake(splat)->wait(60.0));
        EXPECT_EQ(splat_lod::dropin::background_bake(splat)->state(), BackgroundBake::State::cancelled);
        EXPECT_FALSE(splat.update_lod());
        EXPECT_FALSE(splat.cloud->has_lod_attributes());
    }
    EXPECT_TRUE(entries(cache).empty());
    midway = false;
    release = false;
    {
        auto scene = engine->load_scene(scene_file);
        const ReleaseOnExit guard{release};
        const auto job = splat_lod::dropin::background_bake(splat_of(*scene));
        ASSERT_NE(job, nullptr);
        while (!midway && job->state() == BackgroundBake::State::running) std::this_thread::yield();
        EXPECT_TRUE(midway.load());
        release = true;
        scene.reset();  // closing the scene cancels its bake and waits for it
    }
    EXPECT_TRUE(entries(cache).empty());
}

TEST(DropInLod, NoLodKeyDrawsTheFileAsItIs) {
    const fs::path dir = engine::test::output_dir("DropInLod");
    auto settings = quick_settings();
    settings.cache_folder = dir / "cache";
    auto engine = make_engine(settings);
    auto scene = engine->load_scene(write_scene(dir, ""));
    EXPECT_EQ(splat_lod::dropin::background_bake(splat_of(*scene)), nullptr);
    EXPECT_FALSE(splat_of(*scene).cloud->has_lod_attributes());
    EXPECT_FALSE(fs::exists(dir / "cache"));
}

TEST(DropInLod, BadLodValuesAreClearErrors) {
    const fs::path dir = engine::test::output_dir("DropInLod");
    auto engine = make_engine();
    const std::pair<std::string, std::string> cases[] = {
        {R"(, "lod": "fast")", "scene.json: nodes[0].components[0].lod: 'fast' is not a LOD mode (known: auto"},
        {R"(, "lod": "Auto")", "'Auto' is not a LOD mode"},
        {R"(, "lod": 3)", "scene.json: nodes[0].components[0].lod: expected a string, got 3"},
        {R"(, "lod": true)", "lod: expected a string, got true"},
    };
    for (const auto& [keys, expected] : cases) {
        try {
            engine->load_scene(write_scene(dir, keys));
            ADD_FAILURE() << keys << " loaded";
        } catch (const engine::Error& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    }
}

}  // namespace
