// The drop-in LOD's cache (docs/lod.md, "Drop-in LOD"): the folder, the key, and the background bake
// that fills it: a finished bake writes one complete entry, a cancelled or failed one writes nothing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

#include "engine/core/error.h"
#include "splat_lod/bake/lod_cache.h"
#include "splat_lod/core/splat_io.h"
#include "splat_test_data.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using namespace splat_lod;
using bake::BackgroundBake;

// Sets an environment variable for one scope and restores it after.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value)
            ::setenv(name, value, 1);
        else
            ::unsetenv(name);
    }
    ~ScopedEnv() {
        if (old_)
            ::setenv(name_, old_->c_str(), 1);
        else
            ::unsetenv(name_);
    }

private:
    const char* name_;
    std::optional<std::string> old_;
};

// A bake of a couple of seconds: few cameras, small images, few refinement iterations.
bake::BakeSetup quick_setup() {
    bake::BakeSetup setup;
    setup.cameras = "rings:2x4";
    setup.width = 128;
    setup.height = 128;
    setup.options.refine_iterations = 20;
    setup.options.refine_cameras = 4;
    setup.options.threads = 2;
    return setup;
}

std::vector<std::string> entries(const fs::path& folder) {
    std::vector<std::string> names;
    if (!fs::exists(folder)) return names;
    for (const auto& item : fs::directory_iterator(folder)) names.push_back(item.path().filename().string());
    return names;
}

TEST(LodCache, FolderFollowsXdgCacheHomeThenHome) {
    {
        const ScopedEnv xdg("XDG_CACHE_HOME", "/tmp/xdg-cache");
        EXPECT_EQ(bake::lod_cache_folder(), fs::path("/tmp/xdg-cache/splat_engine/lod"));
    }
    const ScopedEnv home("HOME", "/home/someone");
    {
        const ScopedEnv xdg("XDG_CACHE_HOME", nullptr);
        EXPECT_EQ(bake::lod_cache_folder(), fs::path("/home/someone/.cache/splat_engine/lod"));
    }
    {
        const ScopedEnv xdg("XDG_CACHE_HOME", "relative/cache");  // not absolute: ignored, as the spec says
        EXPECT_EQ(bake::lod_cache_folder(), fs::path("/home/someone/.cache/splat_engine/lod"));
    }
    const ScopedEnv no_home("HOME", nullptr);
    const ScopedEnv no_xdg("XDG_CACHE_HOME", nullptr);
    EXPECT_THROW(bake::lod_cache_folder(), engine::Error);
}

TEST(LodCache, KeyDependsOnTheBytesAndTheSettingsOnly) {
    const std::vector<std::uint8_t> bytes{1, 2, 3, 4, 5};
    const bake::BakeSetup setup;
    const std::string key = bake::lod_cache_name(bytes, setup);
    // zlib's CRC-32 and Adler-32 of {1, 2, 3, 4, 5}, then the settings' CRC-32.
    EXPECT_EQ(key.substr(0, 17), "470b99f400280010-");
    EXPECT_EQ(key.size(), 16u + 1u + 8u + 8u);
    EXPECT_EQ(key.substr(25), ".lod.ply");
    EXPECT_EQ(bake::lod_cache_name(bytes, setup), key);
    const std::vector<std::uint8_t> other{1, 2, 3, 4, 6};
    EXPECT_NE(bake::lod_cache_name(other, setup), key);
    bake::BakeSetup threads = setup;
    threads.options.threads = 3;  // does not change the output, so not the key
    EXPECT_EQ(bake::lod_cache_name(bytes, threads), key);
    bake::BakeSetup iterations = setup;
    iterations.options.refine_iterations = 199;
    EXPECT_NE(bake::lod_cache_name(bytes, iterations), key);
    bake::BakeSetup size = setup;
    size.width = 256;
    EXPECT_NE(bake::lod_cache_name(bytes, size), key);
    EXPECT_NE(bake::bake_settings_text(setup).find("format 2;"), std::string::npos)
        << "the version with the level handover";
}

TEST(LodCache, BackgroundBakeWritesOneCompleteEntry) {
    const fs::path folder = engine::test::output_dir("LodCache") / "cache";
    fs::remove_all(folder);
    const fs::path entry = folder / "scene.lod.ply";
    // A temporary that a killed bake of the same entry left (its process no longer runs).
    fs::create_directories(folder);
    { std::ofstream(entry.string() + ".tmp-2147483646-0") << "partial"; }
    const auto fine = std::make_shared<const SplatCloud>(engine::test::lattice_cloud());
    std::atomic<int> reports{0};
    BackgroundBake job(fine, entry, quick_setup(), "scene.ply", [&](const std::string&, double) { ++reports; });
    ASSERT_TRUE(job.wait(120.0));
    ASSERT_EQ(job.state(), BackgroundBake::State::done) << job.error();
    EXPECT_EQ(job.percent(), 100);
    EXPECT_GT(reports.load(), 10);
    const auto baked = job.result();
    ASSERT_NE(baked, nullptr);
    EXPECT_TRUE(baked->has_lod_attributes());
    EXPECT_GT(baked->size(), fine->size());
    EXPECT_EQ(entries(folder), std::vector<std::string>{"scene.lod.ply"});  // no temporaries
    const SplatCloud loaded = load_splat_file(entry);
    EXPECT_EQ(loaded.size(), baked->size());
    EXPECT_EQ(loaded.lod_level, baked->lod_level);
}

TEST(LodCache, CancelledBakeLeavesNoEntry) {
    const fs::path folder = engine::test::output_dir("LodCache") / "cache";
    fs::remove_all(folder);
    std::atomic<bool> midway{false}, cancelled{false};
    const auto fine = std::make_shared<const SplatCloud>(engine::test::lattice_cloud());
    BackgroundBake job(fine, folder / "scene.lod.ply", quick_setup(), "scene.ply",
                       [&](const std::string& stage, double) {
                           if (stage.find("refine level") == std::string::npos) return;
                           midway = true;
                           while (!cancelled) std::this_thread::yield();  // held midway until cancelled
                       });
    while (!midway && job.state() == BackgroundBake::State::running) std::this_thread::yield();
    const auto lines = bake::running_bake_lines();
    job.cancel();
    cancelled = true;
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lines[0].rfind("baking scene.ply: ", 0), 0u) << lines[0];
    EXPECT_EQ(lines[0].substr(lines[0].size() - 2), " %") << lines[0];
    ASSERT_TRUE(job.wait(60.0));
    EXPECT_TRUE(midway.load());
    EXPECT_EQ(job.state(), BackgroundBake::State::cancelled);
    EXPECT_EQ(job.result(), nullptr);
    EXPECT_TRUE(entries(folder).empty());
    EXPECT_TRUE(bake::running_bake_lines().empty());
}

TEST(LodCache, FailedBakeLeavesNoEntryAndNamesTheFile) {
    const fs::path folder = engine::test::output_dir("LodCache") / "cache";
    fs::remove_all(folder);
    const auto fine = std::make_shared<const SplatCloud>(engine::test::lattice_cloud());
    // Failing midway (a hook that throws as a bake step would).
    BackgroundBake failing(fine, folder / "a.lod.ply", quick_setup(), "garden.ply",
                           [](const std::string& stage, double) {
                               if (stage.find("ranges") != std::string::npos) engine::fail("disk on fire");
                           });
    ASSERT_TRUE(failing.wait(60.0));
    EXPECT_EQ(failing.state(), BackgroundBake::State::failed);
    EXPECT_EQ(failing.error(), "garden.ply: disk on fire");
    // Input the bake refuses: it already has LOD attributes.
    auto baked_already = engine::test::lattice_cloud(4);
    baked_already.lod_level.assign(baked_already.size(), 2);
    baked_already.coverage_min.assign(baked_already.size(), -1.0f);
    baked_already.coverage_max.assign(baked_already.size(), -1.0f);
    BackgroundBake refused(std::make_shared<const SplatCloud>(baked_already), folder / "b.lod.ply", quick_setup(),
                           "baked.ply");
    ASSERT_TRUE(refused.wait(60.0));
    EXPECT_EQ(refused.state(), BackgroundBake::State::failed);
    EXPECT_NE(refused.error().find("baked.ply: "), std::string::npos) << refused.error();
    EXPECT_NE(refused.error().find("LOD attributes"), std::string::npos) << refused.error();
    EXPECT_TRUE(entries(folder).empty());
}

TEST(LodCache, UnwritableCacheStillHandsOverTheBake) {
    const fs::path dir = engine::test::output_dir("LodCache");
    std::ofstream(dir / "not_a_folder") << "a file where the cache folder should be";
    BackgroundBake job(std::make_shared<const SplatCloud>(engine::test::lattice_cloud(8)),
                       dir / "not_a_folder" / "scene.lod.ply", quick_setup(), "scene.ply");
    ASSERT_TRUE(job.wait(120.0));
    EXPECT_EQ(job.state(), BackgroundBake::State::done) << job.error();
    ASSERT_NE(job.result(), nullptr);
    EXPECT_TRUE(job.result()->has_lod_attributes());
}

TEST(LodCache, DestroyingARunningBakeCancelsIt) {
    const fs::path folder = engine::test::output_dir("LodCache") / "cache";
    fs::remove_all(folder);
    {
        BackgroundBake job(std::make_shared<const SplatCloud>(engine::test::lattice_cloud()), folder / "scene.lod.ply",
                           quick_setup(), "scene.ply");
    }
    EXPECT_TRUE(entries(folder).empty());
}

// The process itself killed (SIGKILL) in the middle of its bake: nothing runs to clean up, and still no
// entry exists under the cache name; the next bake of the same key writes one complete entry.
TEST(LodCache, KilledBakeProcessLeavesNoEntry) {
    const fs::path folder = engine::test::output_dir("LodCache") / "killed";
    fs::remove_all(folder);
    const fs::path entry = folder / "scene.lod.ply";
    const auto fine = std::make_shared<const SplatCloud>(engine::test::lattice_cloud());
    int pipe_fds[2];
    ASSERT_EQ(::pipe(pipe_fds), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        // The child bakes and says once when it is part-way through the refinement; then it goes on
        // baking until it is killed (or exits with a code the parent reports).
        ::close(pipe_fds[0]);
        bool told = false;
        BackgroundBake job(fine, entry, quick_setup(), "scene.ply", [&](const std::string& stage, double) {
            if (told || stage.find("refine level") == std::string::npos) return;
            told = true;
            const char byte = 'r';
            (void)!::write(pipe_fds[1], &byte, 1);
            ::sleep(60);  // killed here
        });
        job.wait(120.0);
        ::_exit(3);
    }
    ::close(pipe_fds[1]);
    char byte = 0;
    const auto got = ::read(pipe_fds[0], &byte, 1);
    ::close(pipe_fds[0]);
    ::kill(child, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_EQ(got, 1) << "the child never reached the refinement";
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    EXPECT_FALSE(fs::exists(entry));
    BackgroundBake again(fine, entry, quick_setup(), "scene.ply");
    ASSERT_TRUE(again.wait(120.0));
    ASSERT_EQ(again.state(), BackgroundBake::State::done) << again.error();
    EXPECT_EQ(entries(folder), std::vector<std::string>{"scene.lod.ply"});
    EXPECT_EQ(load_splat_file(entry).size(), again.result()->size());
}

}  // namespace
