// Sharded world bakes (world/world_shards.h) on the tiny test world: shards run one after another
// or two at once merge to the unsharded world byte for byte (in a fresh folder and over an older
// world); a merge with a shard missing, a chunk changed or a shard still running fails and writes
// nothing; bad I/N is refused; a shard run again reuses its chunks; the share is a balanced
// partition.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <thread>

#include "engine/core/error.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/worldgen/world_generator.h"
#include "splat_lod/worldgen/world_shards.h"
#include "test_support.h"
#include "tiny_world.h"
#include "world_folder.h"

namespace {

namespace fs = std::filesystem;
using namespace splat_lod::world;
using engine::test::folder_bytes;
using splat_io_test::error_of;

// The tiny world's options (seed 4, one thread per run) in a fresh subfolder of the test's folder.
WorldOptions fresh_options(const std::string& name, std::uint64_t seed = 4) {
    const fs::path dir = engine::test::output_dir("world_shards") / name;
    fs::remove_all(dir);
    return engine::test::tiny_world_options(dir, seed, 1);
}

void bake_shards(const WorldOptions& options, std::size_t count, const std::set<std::size_t>& skip = {}) {
    for (std::size_t i = 1; i <= count; ++i)
        if (!skip.count(i)) bake_world_shard(options, {i, count});
}

// The files a manifest names with their bytes, and the manifest.
std::map<std::string, std::string> world_files(const fs::path& dir) {
    const auto all = folder_bytes(dir);
    const WorldManifest m = read_world_manifest(dir / kManifestFileName);
    std::set<std::string> named = {kManifestFileName};
    for (const ChunkEntry& c : m.chunks) named.insert(c.file.generic_string());
    for (const Prop& p : m.props) named.insert(p.mesh.generic_string());
    if (!m.terrain_mesh.empty()) named.insert(m.terrain_mesh.generic_string());
    std::map<std::string, std::string> files;
    for (const std::string& name : named) files[name] = all.count(name) ? all.at(name) : "(missing)";
    return files;
}

}  // namespace

TEST(WorldShards, ShardsRunInTurnOrTwoAtOnceMergeToTheUnshardedWorldByteForByte) {
    WorldOptions unsharded = fresh_options("unsharded");
    unsharded.threads = 2;
    generate_world(unsharded);
    const auto expected = folder_bytes(unsharded.output);
    ASSERT_TRUE(expected.count("gen-1/chunks/chunk_+000_+000.splatc"));

    const WorldOptions in_turn = fresh_options("in_turn");
    bake_shards(in_turn, 3);
    EXPECT_FALSE(fs::exists(in_turn.output / kManifestFileName)) << "only the merge commits";
    const WorldResult merged = merge_world_shards(in_turn);
    EXPECT_FALSE(merged.summary.cached);
    EXPECT_EQ(merged.summary.chunks, 9u);
    EXPECT_TRUE(folder_bytes(in_turn.output) == expected) << "the whole folder, paths included (gen-1)";

    // Shards 1 and 2 at once (each holds the staging folder's shared lock), then shard 3.
    const WorldOptions at_once = fresh_options("at_once");
    std::string errors[2];
    std::thread first([&] { errors[0] = error_of([&] { bake_world_shard(at_once, {1, 3}); }); });
    std::thread second([&] { errors[1] = error_of([&] { bake_world_shard(at_once, {2, 3}); }); });
    first.join();
    second.join();
    EXPECT_EQ(errors[0] + errors[1], "");
    bake_world_shard(at_once, {3, 3});
    merge_world_shards(at_once);
    EXPECT_TRUE(folder_bytes(at_once.output) == expected);

    // A merge or a shard run again on the committed world does nothing.
    EXPECT_TRUE(merge_world_shards(at_once).summary.cached);
    EXPECT_TRUE(bake_world_shard(at_once, {2, 3}).summary.cached);
    EXPECT_TRUE(folder_bytes(at_once.output) == expected);
}

TEST(WorldShards, OverAnOlderWorldTheMergeTakesTheGenerationAnUnshardedRunWouldAndShardsLeaveTheOldWorldAlone) {
    WorldOptions old_world = fresh_options("sharded", 8);
    generate_world(old_world);
    WorldOptions unsharded_old = fresh_options("unsharded", 8);
    generate_world(unsharded_old);
    fs::create_directories(old_world.output / "gen-3");  // a killed run's: both runs take gen-4
    fs::create_directories(unsharded_old.output / "gen-3");
    const auto old_files = world_files(old_world.output);

    WorldOptions sharded = old_world, unsharded = unsharded_old;
    sharded.seed = unsharded.seed = 4;
    bake_shards(sharded, 2);
    EXPECT_TRUE(world_files(old_world.output) == old_files) << "shards touch nothing the current world names";
    merge_world_shards(sharded);
    generate_world(unsharded);
    EXPECT_EQ(read_world_manifest(sharded.output / kManifestFileName).chunks[0].file.begin()->string(), "gen-4");
    EXPECT_TRUE(folder_bytes(sharded.output) == folder_bytes(unsharded.output));
}

TEST(WorldShards, AMergeWithAShardMissingFailsNamingItAndWritesNothing) {
    const WorldOptions options = fresh_options("missing");
    bake_shards(options, 3, {2});
    const auto before = folder_bytes(options.output);
    const std::string message = error_of([&] { merge_world_shards(options); });
    EXPECT_NE(message.find("missing shards 2/3"), std::string::npos) << message;
    // Shard 2 of 3 holds grid indices 1, 4, 7: cells (0, −1), (0, 0), (0, 1).
    EXPECT_NE(message.find("3 of 9 chunks missing: chunk_+000_-001, chunk_+000_+000, chunk_+000_+001"),
              std::string::npos)
        << message;
    EXPECT_FALSE(fs::exists(options.output / kManifestFileName));
    EXPECT_TRUE(folder_bytes(options.output) == before) << "a failed merge changes nothing";

    const WorldOptions none = fresh_options("none");
    fs::create_directories(none.output);
    EXPECT_NE(error_of([&] { merge_world_shards(none); }).find("no shard of these options has run here"),
              std::string::npos);

    // With the missing shard done, the merge commits.
    bake_world_shard(options, {2, 3});
    EXPECT_EQ(merge_world_shards(options).manifest.chunks.size(), 9u);
}

TEST(WorldShards, AMergeRefusesAChunkThatDoesNotMatchItsRecordAndKeepsTheCurrentWorld) {
    WorldOptions options = fresh_options("corrupt", 8);
    generate_world(options);  // the world the failed merge must keep
    options.seed = 4;
    bake_shards(options, 3);
    const fs::path chunk = options.output / staging_folder(options) / "gen/chunks" / (chunk_id({1, 1}) + ".splatc");
    {
        std::fstream file(chunk, std::ios::in | std::ios::out | std::ios::binary);
        file.seekp(-3, std::ios::end);
        file.put('\x5a');  // same size, other bytes: only the checksums see it
    }
    const auto before = folder_bytes(options.output);
    const std::string message = error_of([&] { merge_world_shards(options); });
    EXPECT_NE(message.find(chunk.string() + ": byte "), std::string::npos) << message;
    EXPECT_NE(message.find("do not match the checksum its shard recorded"), std::string::npos) << message;
    EXPECT_TRUE(folder_bytes(options.output) == before);
    EXPECT_EQ(read_world_manifest(options.output / kManifestFileName).seed, 8u);

    // The shard run again finds its record wrong and bakes its chunks again (the same bytes).
    const WorldResult again = bake_world_shard(options, {3, 3});  // grid index 8: cell (1, 1)
    EXPECT_FALSE(again.summary.cached);
    EXPECT_NE(again.summary.cache_note.find(chunk.string()), std::string::npos) << again.summary.cache_note;
    EXPECT_EQ(merge_world_shards(options).manifest.seed, 4u);
}

TEST(WorldShards, AMergeIsRefusedWhileAShardStillWrites) {
    const WorldOptions options = fresh_options("running");
    bake_shards(options, 2);
    const FolderFlock shard(options.output / staging_folder(options), false);  // as a running shard holds it
    ASSERT_TRUE(shard.held()) << shard.problem();
    const std::string message = error_of([&] { merge_world_shards(options); });
    EXPECT_NE(message.find("a shard is still baking into it"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(options.output / kManifestFileName));
}

TEST(WorldShards, BadShardSpecsAreRefusedWithAClearMessage) {
    EXPECT_EQ(parse_world_shard("3/8").index, 3u);
    EXPECT_EQ(parse_world_shard("3/8").count, 8u);
    EXPECT_EQ(parse_world_shard("1/1").count, 1u);
    for (const char* spec : {"0/3", "4/3"})
        EXPECT_NE(
            error_of([&] {
                parse_world_shard(spec);
            }).find("--shard \"" + std::string(spec) + "\": the shard's index is 1-based: 1 <= I <= N (here 1 to 3)"),
            std::string::npos)
            << spec;
    EXPECT_NE(error_of([] { parse_world_shard("3/0"); }).find("--shard \"3/0\": the number of shards N must be 1 to"),
              std::string::npos);
    for (const char* spec :
         {"x", "", "3", "/3", "1/", "+1/3", " 1/3", "1/3 ", "1/3/5", "-1/3", "1.0/3", "1/99999999999999999999"})
        EXPECT_NE(
            error_of([&] { parse_world_shard(spec); }).find("--shard \"" + std::string(spec) + "\": expected I/N"),
            std::string::npos)
            << spec;
    EXPECT_NE(error_of([] { parse_world_shard("1/2000000"); }).find("N must be 1 to 1048576"), std::string::npos);
    const WorldOptions options = fresh_options("bad");
    EXPECT_NE(error_of([&] { bake_world_shard(options, {0, 3}); }).find("1 <= I <= N"), std::string::npos);
    EXPECT_FALSE(fs::exists(options.output));
}

TEST(WorldShards, AShardRunAgainReusesItsChunksWithoutWriting) {
    const WorldOptions options = fresh_options("again");
    EXPECT_FALSE(bake_world_shard(options, {2, 3}).summary.cached);
    const auto bytes = folder_bytes(options.output);
    std::map<std::string, fs::file_time_type> times;
    for (const auto& [name, content] : bytes) times[name] = fs::last_write_time(options.output / name);
    const WorldResult again = bake_world_shard(options, {2, 3});
    EXPECT_TRUE(again.summary.cached);
    EXPECT_EQ(again.summary.chunks, 3u);
    EXPECT_TRUE(folder_bytes(options.output) == bytes);
    for (const auto& [name, time] : times) EXPECT_EQ(fs::last_write_time(options.output / name), time) << name;

    // --force bakes again: the same bytes.
    WorldOptions forced = options;
    forced.force = true;
    EXPECT_FALSE(bake_world_shard(forced, {2, 3}).summary.cached);
    EXPECT_TRUE(folder_bytes(options.output) == bytes);
}

TEST(WorldShards, TheShareIsABalancedPartitionInGridOrder) {
    for (const std::size_t chunks : {1u, 9u, 256u})
        for (std::size_t count = 1; count <= 12; ++count) {
            std::vector<int> owner(chunks, 0);
            std::size_t smallest = chunks, largest = 0;
            for (std::size_t index = 1; index <= count; ++index) {
                const auto mine = shard_chunk_indices(chunks, {index, count});
                smallest = std::min(smallest, mine.size());
                largest = std::max(largest, mine.size());
                for (const std::size_t k : mine) {
                    ++owner[k];
                    EXPECT_EQ(k % count, index - 1);
                }
            }
            EXPECT_EQ(std::count(owner.begin(), owner.end(), 1), static_cast<long>(chunks)) << chunks << " " << count;
            EXPECT_LE(largest - smallest, 1u) << chunks << " " << count;
        }
    EXPECT_EQ(shard_record_name({3, 8}), "shard-3-of-8.json");
    const WorldOptions a = fresh_options("names"), b = fresh_options("names", 5);
    EXPECT_EQ(staging_folder(a).string().rfind("staging-", 0), 0u);
    EXPECT_EQ(staging_folder(a).string().size(), 8u + 16u);
    EXPECT_NE(staging_folder(a), staging_folder(b));
}
