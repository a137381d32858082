// The soak run (sample_game/harness/soak_run.h) on the tests' tiny world through the real engine: a short
// version of `sample_game_harness --soak`. Laps with chunk files removed, truncated, replaced and corrupted
// underneath the streamer must end like the first: same GL objects, flat memory, every chunk back, the same
// frame. A leak made on purpose must fail the run, so the checks can fail.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/gl/objects.h"
#include "gpu_fixture.h"
#include "sample_game/harness/frame_record.h"
#include "sample_game/harness/soak_run.h"
#include "splat_lod/stream/stream_policy.h"
#include "splat_lod/worldgen/world_generator.h"
#include "test_support.h"
#include "tiny_world.h"

namespace sw = splat_lod::world;
using namespace sample_game;

namespace {

// The message of the engine::Error that `run` throws ("" when it throws none).
template <class F>
std::string error_of(F run) {
    try {
        run();
    } catch (const engine::Error& e) {
        return e.what();
    }
    return "";
}

class SoakTest : public engine::test::GpuTest {};

SoakOptions short_soak(const std::string& name) {
    SoakOptions o;
    o.world = engine::test::cached_tiny_world("tiny_world");
    o.out = engine::test::output_dir("sample_game") / name;
    o.width = 320;
    o.height = 180;
    o.frames_per_lap = 40;
    o.laps = 4;
    o.sample_every = 4;
    o.settings.sync_streaming = true;  // repeatable laps
    o.settings.retry_failed_after_frames = 6;
    // A binding memory budget (about half the world): levels near the start are evicted while the
    // camera is away and read again when it comes back, while their files are damaged.
    const sw::WorldManifest manifest = sw::read_world_manifest(o.world / sw::kManifestFileName);
    std::uint64_t whole = 0;
    for (const auto& c : manifest.chunks)
        for (int l = 1; l <= sw::kLevels; ++l) {
            const std::uint64_t count = c.prefix_count[static_cast<std::size_t>(l - 1)] -
                                        (l < sw::kLevels ? c.prefix_count[static_cast<std::size_t>(l)] : 0);
            whole += sw::gpu_bytes(count, 0, sw::PageLayout{});
        }
    o.settings.memory_budget_bytes = whole / 2;
    return o;
}

}  // namespace

TEST_F(SoakTest, LapsWithDamagedChunkFilesEndLikeTheFirst) {
    SoakOptions o = short_soak("soak");
    const auto before = engine::test::folder_bytes(o.world);
    const SoakOutcome outcome = run_soak(o, nullptr);
    SCOPED_TRACE(outcome.summary_text);
    EXPECT_TRUE(outcome.passed);
    ASSERT_EQ(outcome.lap_ends.size(), 4u);
    for (const auto& line : outcome.checks) EXPECT_EQ(line.rfind("PASS", 0), 0u) << line;
    // The faults were noticed, each kind, on the damaged chunks only.
    EXPECT_GT(outcome.failures_removed, 0u);
    EXPECT_GT(outcome.failures_truncated, 0u);
    EXPECT_GT(outcome.failures_replaced, 0u);
    EXPECT_GT(outcome.failures_corrupted, 0u);
    EXPECT_EQ(outcome.failures_undamaged, 0u);
    EXPECT_EQ(outcome.lap_ends.back().failed_chunks, 0u);
    // The user's world was never touched: the faults went to the linked copy.
    EXPECT_TRUE(engine::test::folder_bytes(o.world) == before);
    for (const char* name : {"soak.csv", "soak_summary.txt", "lap_end_first.png", "lap_end_last.png"})
        EXPECT_TRUE(std::filesystem::exists(o.out / name)) << name;
    const CsvTable csv = read_csv(o.out / "soak.csv");
    EXPECT_EQ(csv.rows.size(), 4u * (40u / 4u + 1u)) << "a row every 4 frames and one per lap end";
}

TEST_F(SoakTest, ALeakedBufferEveryLapFailsTheRun) {
    SoakOptions o = short_soak("soak_leak");
    o.faults = false;
    o.laps = 3;
    std::vector<GLuint> leaked;
    o.after_lap = [&](int) {
        engine::gl::Buffer buffer("soak test leak");
        buffer.storage(4u << 20);
        leaked.push_back(buffer.release());  // 4 MiB that nobody deletes
    };
    const SoakOutcome outcome = run_soak(o, nullptr);
    SCOPED_TRACE(outcome.summary_text);
    EXPECT_FALSE(outcome.passed);
    ASSERT_GE(outcome.checks.size(), 2u);
    EXPECT_EQ(outcome.checks[0].rfind("FAIL GL objects", 0), 0u) << outcome.checks[0];
    EXPECT_EQ(outcome.checks[1].rfind("FAIL GL memory", 0), 0u) << outcome.checks[1];
    glDeleteBuffers(static_cast<GLsizei>(leaked.size()), leaked.data());
}

TEST(SoakOptionsTest, ImpossibleSettingsNameTheOption) {
    SoakOptions o;
    o.world = "nowhere";
    o.laps = 2;
    EXPECT_NE(error_of([&] { validate(o); }).find("--laps must be at least 3 with faults"), std::string::npos);
    o.laps = 3;
    o.frames_per_lap = 5;
    EXPECT_NE(error_of([&] { validate(o); }).find("--frames (per soak lap) must be at least 20"), std::string::npos);
    o.frames_per_lap = 100;
    o.settings.retry_failed_after_frames = 0;
    EXPECT_NE(error_of([&] { validate(o); }).find("needs retries"), std::string::npos);
    o.settings.retry_failed_after_frames = 301;
    EXPECT_NE(error_of([&] { validate(o); }).find("must be at most 300 frames"), std::string::npos);
}
