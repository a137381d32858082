// Output safety (world/world_generator.h, engine/core/file_io.h), in process: a failed world run
// leaves the previous world byte for byte; after a commit only the new world's files remain
// (previous generation, leftovers of killed runs and flat-layout files removed, other files kept); a
// cached run removes what a run killed after its commit left; worlds of the flat layout still read;
// a second run into a locked folder fails, and so does a run into a folder a program streams.
// Atomic writes keep permissions, use unique temporaries
// and remove them on failure; temporaries of dead writers are found. The kill tests with real
// processes: engine/plugins/splat_lod/tests/tools/output_safety_kill_test.cpp.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <thread>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/world_lock.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/worldgen/world_generator.h"
#include "test_support.h"
#include "tiny_world.h"

namespace {

namespace fs = std::filesystem;
using namespace splat_lod::world;
using engine::test::folder_bytes;
using engine::test::without_generation;
using splat_io_test::error_of;

void touch(const fs::path& path, const std::string& text = "left over") {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

std::set<std::string> names(const std::map<std::string, std::string>& files) {
    std::set<std::string> result;
    for (const auto& item : files) result.insert(item.first);
    return result;
}

// The tiny test world (seed 4) generated afresh in the tests' world_safety folder; its options.
WorldOptions fresh_world(int threads = 2, ChunkCodec codec = ChunkCodec::compact) {
    const fs::path dir = engine::test::output_dir("world_safety");
    fs::remove_all(dir);
    WorldOptions options = engine::test::tiny_world_options(dir, 4, threads);
    options.chunk_codec = codec;
    generate_world(options);
    return options;
}

bool has_temporary(const fs::path& folder) {
    for (const auto& item : fs::recursive_directory_iterator(folder))
        if (item.path().filename().string().find(".tmp-") != std::string::npos) return true;
    return false;
}

}  // namespace

TEST(WorldOutputSafety, AFailedRunLeavesThePreviousWorldByteForByte) {
    WorldOptions options = fresh_world(1);
    const fs::path dir = options.output;
    const auto before = folder_bytes(dir);
    ASSERT_TRUE(before.count("gen-1/chunks/chunk_+000_+000.splatc"));
    options.seed = 8;

    // A chunk write that fails after the meshes and four chunks of the run were written: the next
    // run writes into gen-2, and a folder stands where its chunk (0, 0) must go.
    options.progress = [&](const WorldProgress& p) {
        if (p.stage == "meshes")
            fs::create_directories(dir / "gen-2" / "chunks" / (chunk_id({0, 0}) + ".splatc") / "x");
    };
    const std::string message = error_of([&] { generate_world(options); });
    EXPECT_NE(message.find(chunk_id({0, 0})), std::string::npos) << message;
    EXPECT_TRUE(folder_bytes(dir) == before) << "the failed run changed or left files";
    EXPECT_FALSE(fs::exists(dir / "gen-2"));

    // A failure after every chunk was written, just before the commit.
    options.progress = [](const WorldProgress& p) {
        if (p.stage == "manifest") engine::fail("interrupted before the commit");
    };
    EXPECT_NE(error_of([&] { generate_world(options); }).find("interrupted"), std::string::npos);
    EXPECT_TRUE(folder_bytes(dir) == before) << "the failed run changed or left files";
    EXPECT_EQ(read_world_manifest(dir / kManifestFileName).seed, 4u);
}

TEST(WorldOutputSafety, ACommittedRunRemovesThePreviousGenerationAndLeftoversButNothingElse) {
    WorldOptions options = fresh_world();
    const fs::path dir = options.output;
    touch(dir / "gen-5/chunks/chunk_+000_+000.lod.ply");  // a killed run's
    touch(dir / "gen-5/meshes/house.glb.tmp-123-0");
    touch(dir / "world.json.tmp-99999-0");
    touch(dir / "chunks/chunk_+001_+000.lod.ply");  // the flat layout of earlier versions
    touch(dir / "chunks/chunk_+001_+000.lod.ply.tmp-77");
    touch(dir / "meshes/terrain.glb");
    touch(dir / "notes.txt");  // not the generator's
    touch(dir / "chunks/readme.txt");
    touch(dir / "gen-x/keep.txt");

    options.seed = 8;
    const WorldResult world = generate_world(options);
    EXPECT_FALSE(world.summary.cached);
    const auto after = folder_bytes(dir);
    std::set<std::string> expected = {"world.json", "notes.txt", "chunks/readme.txt", "gen-x/keep.txt"};
    for (const ChunkEntry& c : world.manifest.chunks) expected.insert(c.file.generic_string());
    for (const ChunkEntry& g : world.manifest.groups) expected.insert(g.file.generic_string());
    for (const char* mesh : {"house", "fence", "post", "terrain"})  // all written, placed or not
        expected.insert("gen-6/meshes/" + std::string(mesh) + ".glb");
    EXPECT_EQ(names(after), expected);
    EXPECT_EQ(expected.size(), 4u + 9u + 4u + 5u);
    EXPECT_EQ(world.manifest.chunks[0].file.begin()->string(), "gen-6");
    EXPECT_FALSE(fs::exists(dir / "meshes")) << "emptied, so removed";
}

TEST(WorldOutputSafety, ACachedRunRemovesWhatARunKilledAfterItsCommitLeft) {
    const WorldOptions options = fresh_world();
    const fs::path dir = options.output;
    const auto bytes = folder_bytes(dir);
    std::map<std::string, fs::file_time_type> times;
    for (const auto& [name, content] : bytes) times[name] = fs::last_write_time(dir / name);
    touch(dir / "gen-7/chunks/chunk_+000_+000.lod.ply");
    touch(dir / "world.json.tmp-99999-0");

    EXPECT_TRUE(generate_world(options).summary.cached);
    EXPECT_TRUE(folder_bytes(dir) == bytes);
    for (const auto& [name, time] : times) EXPECT_EQ(fs::last_write_time(dir / name), time) << name << " was rewritten";
}

TEST(WorldOutputSafety, WorldsOfTheFlatLayoutStillReadAndAreReplaced) {
    // Those worlds had PLY chunks.
    WorldOptions options = fresh_world(2, ChunkCodec::ply);
    const fs::path dir = options.output;
    // What earlier versions wrote: chunks/ and meshes/ beside world.json, the manifest naming them,
    // and no chunk groups.
    fs::rename(dir / "gen-1/chunks", dir / "chunks");
    fs::rename(dir / "gen-1/meshes", dir / "meshes");
    fs::remove_all(dir / "gen-1");
    WorldManifest m = read_world_manifest(dir / kManifestFileName);
    for (ChunkEntry& c : m.chunks) c.file = c.file.lexically_relative("gen-1");
    for (Prop& p : m.props) p.mesh = p.mesh.lexically_relative("gen-1");
    m.terrain_mesh = m.terrain_mesh.lexically_relative("gen-1");
    m.groups.clear();
    m.group_generator.clear();
    write_world_manifest(dir / kManifestFileName, m);
    const auto flat = folder_bytes(dir);
    ASSERT_TRUE(flat.count("chunks/chunk_+000_+000.lod.ply"));

    // The cached chunks and meshes stay where they are; only the groups are made, in a generation.
    const WorldResult cached = generate_world(options);
    EXPECT_TRUE(cached.summary.cached);
    EXPECT_TRUE(cached.summary.groups_rebuilt);
    const auto with_groups = folder_bytes(dir);
    for (const auto& [name, bytes] : flat) {
        if (name == kManifestFileName) continue;
        EXPECT_TRUE(with_groups.count(name) && with_groups.at(name) == bytes) << name;
    }
    EXPECT_TRUE(fs::is_directory(dir / "gen-1/groups"));
    EXPECT_TRUE(generate_world(options).summary.cached);
    EXPECT_TRUE(folder_bytes(dir) == with_groups);
    options.force = true;
    EXPECT_FALSE(generate_world(options).summary.cached);
    EXPECT_TRUE(fs::is_directory(dir / "gen-2"));
    EXPECT_FALSE(fs::exists(dir / "gen-1"));
    EXPECT_FALSE(fs::exists(dir / "chunks"));
    EXPECT_FALSE(fs::exists(dir / "meshes"));
    EXPECT_TRUE(without_generation(folder_bytes(dir)) == without_generation(with_groups))
        << "the same world, moved into gen-2";
}

TEST(WorldOutputSafety, ASecondRunIntoALockedFolderFailsAndTheCacheStillServes) {
    const WorldOptions options = fresh_world();
    const fs::path dir = options.output;
    touch(dir / "gen-9/chunks/chunk_+000_+000.lod.ply");  // as if another run were writing it
    const auto bytes = folder_bytes(dir);

    std::optional<WorldFolderLock> other_run(std::in_place, dir, WorldFolderLock::Mode::write);
    ASSERT_TRUE(other_run->held()) << other_run->problem();
    WorldOptions other = options;
    other.seed = 8;
    const std::string message = error_of([&] { generate_world(other); });
    EXPECT_NE(message.find("another run"), std::string::npos) << message;
    EXPECT_TRUE(generate_world(options).summary.cached);
    EXPECT_TRUE(folder_bytes(dir) == bytes) << "nothing may be written or removed without the lock";
    other_run.reset();

    EXPECT_TRUE(generate_world(options).summary.cached);
    EXPECT_FALSE(fs::exists(dir / "gen-9"));
}

// A program streaming the world holds the folder's shared lock (world_lock.h): a regeneration
// would remove the files under it, so it is refused while a cached run still serves; and a
// program cannot start streaming while a run writes.
TEST(WorldOutputSafety, ARunIntoAFolderBeingStreamedFailsAndStreamingWaitsForARun) {
    const WorldOptions options = fresh_world();
    const fs::path dir = options.output;
    const auto bytes = folder_bytes(dir);
    {
        const WorldFolderLock game(dir, WorldFolderLock::Mode::stream);
        ASSERT_TRUE(game.held()) << game.problem();
        const WorldFolderLock second_game(dir, WorldFolderLock::Mode::stream);
        EXPECT_TRUE(second_game.held()) << "any number of programs may stream one world";
        WorldOptions forced = options;
        forced.force = true;
        const std::string message = error_of([&] { generate_world(forced); });
        EXPECT_NE(message.find(dir.string()), std::string::npos) << message;
        EXPECT_NE(message.find("a program is streaming this world"), std::string::npos) << message;
        EXPECT_TRUE(generate_world(options).summary.cached);
        EXPECT_TRUE(folder_bytes(dir) == bytes) << "nothing may be written or removed under a streaming program";
    }
    {
        const WorldFolderLock run(dir, WorldFolderLock::Mode::write);
        ASSERT_TRUE(run.held()) << run.problem();
        const WorldFolderLock game(dir, WorldFolderLock::Mode::stream);
        EXPECT_FALSE(game.held());
        EXPECT_NE(game.problem().find("the world generator is writing"), std::string::npos) << game.problem();
        EXPECT_NE(error_of([&] { game.require(); }).find(dir.string() + ": the world generator"), std::string::npos);
    }
    WorldOptions forced = options;
    forced.force = true;
    EXPECT_FALSE(generate_world(forced).summary.cached) << "with the locks gone, a run may write again";
    const WorldFolderLock missing(dir / "absent", WorldFolderLock::Mode::stream);
    EXPECT_FALSE(missing.held());
    EXPECT_NE(missing.problem().find("cannot open the world's folder"), std::string::npos) << missing.problem();
}

TEST(OutputSafety, AtomicWritesKeepPermissionsUseUniqueTemporariesAndCleanUpOnFailure) {
    const fs::path dir = engine::test::output_dir("output_safety");
    fs::remove_all(dir);
    const fs::path file = dir / "new/folder/file.txt";  // missing folders are made
    engine::write_text_file_atomic(file, "one");
    ASSERT_EQ(::chmod(file.c_str(), 0640), 0);
    engine::write_text_file_atomic(file, "two");
    struct stat info {};
    ASSERT_EQ(::stat(file.c_str(), &info), 0);
    EXPECT_EQ(info.st_mode & 0777, 0640u);
    EXPECT_EQ(engine::read_text_file(file), "two");

    // Threads writing the same files at once: each write is whole, whichever comes last.
    std::vector<std::thread> writers;
    for (int t = 0; t < 6; ++t)
        writers.emplace_back([&dir, t] {
            for (int i = 0; i < 30; ++i)
                engine::write_text_file_atomic(dir / ("shared_" + std::to_string(i % 5)),
                                               std::string(1000 + t, 'a' + t));
        });
    for (auto& writer : writers) writer.join();
    for (int i = 0; i < 5; ++i) {
        const std::string text = engine::read_text_file(dir / ("shared_" + std::to_string(i)));
        ASSERT_GE(text.size(), 1000u);
        EXPECT_EQ(text, std::string(text.size(), static_cast<char>('a' + (text.size() - 1000)))) << i;
    }

    fs::create_directories(dir / "a_folder/inside");
    EXPECT_NE(error_of([&] { engine::write_text_file_atomic(dir / "a_folder", "x"); }).find("a_folder"),
              std::string::npos);
    EXPECT_FALSE(has_temporary(dir));
}

TEST(OutputSafety, TemporariesOfDeadWritersAreRemovedAndLiveOnesKept) {
    const fs::path dir = engine::test::output_dir("output_safety");
    fs::remove_all(dir);
    const pid_t dead = ::fork();
    if (dead == 0) ::_exit(0);
    ASSERT_GT(dead, 0);
    ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);
    const std::string d = std::to_string(dead), live = std::to_string(::getpid());
    const std::vector<std::string> files = {
        "out.ply.tmp-" + d + "-0",   "out.ply.tmp-" + d, "out.ply.tmp-" + live + "-5",
        "other.ply.tmp-" + d + "-0", "out.ply.tmp-abc",  "out.ply"};
    for (const std::string& name : files) touch(dir / name);
    EXPECT_EQ(engine::remove_stale_temporaries(dir / "out.ply"), 2u);
    EXPECT_EQ(names(folder_bytes(dir)),
              (std::set<std::string>{"out.ply.tmp-" + live + "-5", "other.ply.tmp-" + d + "-0", "out.ply.tmp-abc",
                                     "out.ply"}));
}
