// The sample world: the manifest (round trip, every kind of bad input), describe_chunk and
// read_chunk_range against whole-file loads, and tiny generated worlds (same seed → same bytes for
// any thread count, the cache and its invalidation, props that the engine's glTF loader loads,
// nothing but ground inside a house). Failed, killed and concurrent runs: world_output_safety_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <regex>

#include <nlohmann/json.hpp>

#include "splat_io_test_helpers.h"
#include "engine/assets/mesh_asset.h"
#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/gaussian_extent.h"
#include "splat_lod/worldgen/world_generator.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/worldgen/world_terrain.h"
#include "test_support.h"
#include "tiny_world.h"
#include "chunk_content.h"
#include "world_layout.h"
#include "splat_lod/worldgen/world_meshes.h"

namespace {

namespace fs = std::filesystem;
using namespace splat_lod;
using namespace splat_lod::world;
using engine::test::folder_bytes;
using engine::test::without_generation;
using nlohmann::json;

using splat_io_test::error_of;  // the engine::Error message, "" when none

// A manifest with two chunks and a prop; nothing on disk needs to exist for the manifest alone.
WorldManifest sample_manifest() {
    WorldManifest m;
    m.seed = 18446744073709551615ull;  // needs all 64 bits: must not pass through a double
    m.size_m = 128.0f;
    m.chunk_size_m = 64.0f;
    m.density = 0.25f;
    m.generator = "test";
    for (int k = 0; k < 2; ++k) {
        ChunkEntry c;
        c.cell = {k - 1, 0};
        c.id = chunk_id(c.cell);
        c.file = fs::path("chunks") / (c.id + ".lod.ply");
        c.bounds_min = {-64.0f + 64.0f * static_cast<float>(k), -3.5f, -64.0f};
        c.bounds_max = c.bounds_min + glm::vec3(64.0f, 12.25f, 64.0f);
        c.prefix_count = {5000u + static_cast<unsigned>(k), 40, 12, 3};
        c.levels[0] = {0.125f, -1.0f};
        c.levels[3] = {2.5f, 0.0625f};
        c.header_bytes = 700;
        c.vertex_bytes = 77;
        c.file_bytes = c.prefix_bytes(1);
        c.header_crc32 = 0xdeadbeefu - static_cast<unsigned>(k);
        for (std::uint64_t b = 0; b < record_block_count(c); ++b)
            c.record_crc32.push_back(0xfffffff0u + static_cast<unsigned>(b));
        m.gaussians += c.prefix_count[0];
        m.chunks.push_back(c);
    }
    m.props.push_back({"meshes/house.glb", {1.5f, 2.0f, -3.0f}, {0.0f, 37.0f, 0.0f}, {1.0f, 1.0f, 1.25f}});
    m.terrain_mesh = "meshes/terrain.glb";
    return m;
}

WorldOptions tiny_options(const fs::path& folder, std::uint64_t seed, int threads) {
    return engine::test::tiny_world_options(folder, seed, threads);
}

void expect_same_gaussian(const SplatCloud& a, std::size_t i, const SplatCloud& b, std::size_t j) {
    EXPECT_EQ(a.positions[i], b.positions[j]);
    EXPECT_EQ(a.log_scales[i], b.log_scales[j]);
    EXPECT_EQ(a.opacity_logits[i], b.opacity_logits[j]);
    EXPECT_EQ(a.sh_dc[i], b.sh_dc[j]);
    EXPECT_EQ(a.rotations[i].w, b.rotations[j].w);
    EXPECT_EQ(a.rotations[i].z, b.rotations[j].z);
    EXPECT_EQ(a.lod_level[i], b.lod_level[j]);
    EXPECT_EQ(a.coverage_min[i], b.coverage_min[j]);
    EXPECT_EQ(a.coverage_max[i], b.coverage_max[j]);
}

}  // namespace

TEST(WorldManifest, RoundTripKeepsEveryField) {
    const fs::path path = engine::test::output_dir("world") / "world.json";
    const WorldManifest m = sample_manifest();
    write_world_manifest(path, m);
    const WorldManifest r = read_world_manifest(path);
    EXPECT_EQ(r.version, kManifestVersion);
    EXPECT_EQ(r.seed, m.seed);
    EXPECT_EQ(r.size_m, m.size_m);
    EXPECT_EQ(r.chunk_size_m, m.chunk_size_m);
    EXPECT_EQ(r.density, m.density);
    EXPECT_EQ(r.generator, m.generator);
    EXPECT_EQ(r.gaussians, m.gaussians);
    EXPECT_EQ(r.terrain_mesh, m.terrain_mesh);
    ASSERT_EQ(r.chunks.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
        const ChunkEntry &a = m.chunks[k], &b = r.chunks[k];
        EXPECT_EQ(a.id, b.id);
        EXPECT_EQ(a.file, b.file);
        EXPECT_EQ(a.cell, b.cell);
        EXPECT_EQ(a.bounds_min, b.bounds_min);
        EXPECT_EQ(a.bounds_max, b.bounds_max);
        EXPECT_EQ(a.prefix_count, b.prefix_count);
        for (int l = 0; l < kLevels; ++l) {
            EXPECT_EQ(a.levels[l].extent_max, b.levels[l].extent_max);
            EXPECT_EQ(a.levels[l].extent_per_min_coverage_max, b.levels[l].extent_per_min_coverage_max);
        }
        EXPECT_EQ(a.header_bytes, b.header_bytes);
        EXPECT_EQ(a.vertex_bytes, b.vertex_bytes);
        EXPECT_EQ(a.file_bytes, b.file_bytes);
        EXPECT_EQ(a.header_crc32, b.header_crc32);
        EXPECT_EQ(a.record_crc32, b.record_crc32);
        EXPECT_EQ(b.record_crc32.size(), 8u) << "levels 4, 3, 2: one block each; level 1: 4960 records in 5";
    }
    ASSERT_EQ(r.props.size(), 1u);
    EXPECT_EQ(r.props[0].mesh, m.props[0].mesh);
    EXPECT_EQ(r.props[0].translation, m.props[0].translation);
    EXPECT_EQ(r.props[0].rotation_euler_deg, m.props[0].rotation_euler_deg);
    EXPECT_EQ(r.props[0].scale, m.props[0].scale);
    EXPECT_EQ(chunk_id({3, -2}), "chunk_+003_-002");
}

TEST(WorldManifest, EveryBadInputNamesTheFileAndTheKey) {
    const fs::path dir = engine::test::output_dir("world");
    write_world_manifest(dir / "good.json", sample_manifest());
    const json good = json::parse(engine::read_text_file(dir / "good.json"));
    struct Case {
        const char* name;
        std::function<void(json&)> mutate;
        const char* key;  // expected in the message
    };
    const std::vector<Case> cases = {
        {"version", [](json& j) { j["version"] = 1; }, "version"},
        {"reach_order", [](json& j) { j["stream_levels"]["reach_min"][2] = 50; }, "stream_levels"},
        {"reach_count", [](json& j) { j["stream_levels"]["reach_min"] = {0.4, 0.1}; }, "stream_levels.reach_min"},
        {"no_rule", [](json& j) { j.erase("stream_levels"); }, "stream_levels: missing"},
        {"unknown_top", [](json& j) { j["sizem"] = 3; }, "sizem: unknown key"},
        {"unknown_chunk", [](json& j) { j["chunks"][1]["colour"] = 1; }, "chunks[1].colour: unknown key"},
        {"missing", [](json& j) { j.erase("seed"); }, "seed: missing"},
        {"wrong_type", [](json& j) { j["size_m"] = "large"; }, "size_m"},
        {"negative_size", [](json& j) { j["chunk_size_m"] = -64; }, "chunk_size_m"},
        {"negative_count", [](json& j) { j["chunks"][0]["header_bytes"] = -1; }, "chunks[0].header_bytes"},
        {"nan", [](json& j) { j["chunks"][0]["bounds_min"][1] = nullptr; }, "chunks[0].bounds_min[1]"},
        {"nan_extent", [](json& j) { j["chunks"][0]["levels"][2]["extent_max"] = nullptr; }, "chunks[0].levels[2].extent_max"},
        {"prefix_order", [](json& j) { j["chunks"][1]["prefix_count"][2] = 41; }, "chunks[1].prefix_count"},
        {"file_bytes", [](json& j) { j["chunks"][0]["file_bytes"] = 5; }, "chunks[0].file_bytes"},
        {"total", [](json& j) { j["gaussians"] = 7; }, "gaussians"},
        {"escape", [](json& j) { j["chunks"][0]["file"] = "chunks/../../secret.ply"; }, "chunks[0].file"},
        {"absolute", [](json& j) { j["chunks"][1]["file"] = "/etc/passwd"; }, "chunks[1].file"},
        {"prop_escape", [](json& j) { j["props"][0]["mesh"] = "../house.glb"; }, "props[0].mesh"},
        {"duplicate", [](json& j) { j["chunks"][1]["id"] = j["chunks"][0]["id"]; }, "chunks[1].id"},
        {"seed_sign", [](json& j) { j["seed"] = -3; }, "seed"},
        {"no_header_crc", [](json& j) { j["chunks"][0].erase("header_crc32"); }, "chunks[0].header_crc32: missing"},
        {"crc_range", [](json& j) { j["chunks"][1]["record_crc32"][3] = 4294967296ull; }, "chunks[1].record_crc32[3]"},
        {"crc_count", [](json& j) { j["chunks"][0]["record_crc32"].erase(0); }, "chunks[0].record_crc32: holds 7"},
        {"crc_type", [](json& j) { j["chunks"][0]["record_crc32"] = 3; }, "chunks[0].record_crc32"},
        {"old_version", [](json& j) { j["version"] = 2; }, "generate the world again"},
    };
    for (const Case& c : cases) {
        json document = good;
        c.mutate(document);
        const fs::path path = dir / (std::string(c.name) + ".json");
        engine::write_text_file_atomic(path, document.dump());
        const std::string message = error_of([&] { read_world_manifest(path); });
        EXPECT_NE(message.find(path.string()), std::string::npos) << c.name << ": " << message;
        EXPECT_NE(message.find(c.key), std::string::npos) << c.name << ": " << message;
    }
    engine::write_text_file_atomic(dir / "broken.json", "{\"version\": 1, ");
    EXPECT_NE(error_of([&] { read_world_manifest(dir / "broken.json"); }).find("invalid JSON"), std::string::npos);
    EXPECT_NE(error_of([&] { read_world_manifest(dir / "absent.json"); }).find("absent.json"), std::string::npos);
}

TEST(WorldManifest, WriterRefusesWhatTheReaderWouldAndWritesNothing) {
    const fs::path path = engine::test::output_dir("world") / "world.json";
    WorldManifest m = sample_manifest();
    m.chunks[0].prefix_count[1] = m.chunks[0].prefix_count[0] + 1;
    EXPECT_NE(error_of([&] { write_world_manifest(path, m); }).find("chunks[0].prefix_count"), std::string::npos);
    EXPECT_FALSE(fs::exists(path));
}

TEST(WorldManifest, RecordBlocksRestartAtEveryStreamLevelAndCoverARangeExactly) {
    ChunkEntry c;
    const std::uint64_t B = kChecksumBlockRecords;
    // Stream level 4: 2·B + 5 records, level 3: none, level 2: B, level 1: 3 records.
    c.prefix_count = {3 * B + 8, 3 * B + 5, 2 * B + 5, 2 * B + 5};
    EXPECT_EQ(record_block_count(c), 3u + 0u + 1u + 1u);
    const auto all = record_blocks(c, 0, c.prefix_count[0]);
    const std::vector<std::pair<std::uint64_t, std::uint64_t>> expected = {
        {0, B}, {B, 2 * B}, {2 * B, 2 * B + 5}, {2 * B + 5, 3 * B + 5}, {3 * B + 5, 3 * B + 8}};
    ASSERT_EQ(all.size(), expected.size());
    for (std::size_t b = 0; b < all.size(); ++b) {
        EXPECT_EQ(all[b].begin, expected[b].first) << b;
        EXPECT_EQ(all[b].end, expected[b].second) << b;
        EXPECT_EQ(all[b].index, b);
    }
    // A stream level alone reads exactly its own blocks; another range is widened to whole blocks.
    const auto [begin2, end2] = level_range(c, 2);
    const auto level2 = record_blocks(c, begin2, end2);
    ASSERT_EQ(level2.size(), 1u);
    EXPECT_EQ(level2[0].begin, begin2);
    EXPECT_EQ(level2[0].end, end2);
    EXPECT_EQ(level2[0].index, 3u);
    const auto window = record_blocks(c, B - 1, 2 * B + 6);
    ASSERT_EQ(window.size(), 4u);
    EXPECT_EQ(window.front().begin, 0u);
    EXPECT_EQ(window.back().end, 3 * B + 5);
    EXPECT_TRUE(record_blocks(c, 7, 7).empty());
    EXPECT_THROW(record_blocks(c, 0, c.prefix_count[0] + 1), engine::Error);
    EXPECT_EQ(record_block_count(ChunkEntry{}), 0u);
}

TEST(WorldChunk, DescribeRefusesAFileNotInStreamOrder) {
    const fs::path dir = engine::test::output_dir("world");
    SplatCloud cloud;
    cloud.resize(3);
    // Bake levels 1, 4, 1 of millimetre Gaussians: the level-4 one (reach ∞, stream level 4) must
    // come before the others (reach < 0.01 m/px, stream level 1).
    cloud.lod_level = {1, 4, 1};
    cloud.coverage_min = {1.0f, 1.0f, 1.0f};
    cloud.log_scales.assign(3, glm::vec3(std::log(0.001f)));
    write_inria_ply(dir / "bad.lod.ply", cloud);
    const std::string message = error_of([&] { describe_chunk(cloud, dir, "bad.lod.ply", {0, 0}, {}); });
    EXPECT_NE(message.find("bad.lod.ply"), std::string::npos) << message;
    EXPECT_NE(message.find("stream order"), std::string::npos) << message;
}

// The reach of docs/algorithms.md §3's "not too small" test and the split into stream levels: a Gaussian of
// stream level l < 4 is never selectable beyond reach·f, and nothing the coarsest level holds is left
// out of stream level 4.
TEST(WorldChunk, StreamLevelsFollowTheReachOfTheNotTooSmallTest) {
    SplatCloud cloud;
    cloud.resize(5);
    StreamLevelRule rule;  // S_T 2, S_rel_min 0.5
    rule.reach_min = {0.4f, 0.12f, 0.04f};
    // Opacity logit 2 and equal scales σ: extent e = sqrt(2·ln(255·o))·σ.
    const double root_l = std::sqrt(2.0 * std::log(255.0 / (1.0 + std::exp(-2.0))));
    const double extents[] = {0.01, 0.1, 0.3, 1.0, 0.01};
    const float coverage_min[] = {100.0f, 100.0f, 100.0f, 100.0f, 0.5f};
    for (std::size_t i = 0; i < 5; ++i) {
        cloud.lod_level[i] = 1;
        cloud.opacity_logits[i] = 2.0f;
        cloud.log_scales[i] = glm::vec3(static_cast<float>(std::log(extents[i] / root_l)));
        cloud.coverage_min[i] = coverage_min[i];
    }
    // reach = 2·e / min(S_T, S_rel_min·S_min): e for S_min = 100, 2·e / 0.25 = 8·e for S_min = 0.5.
    for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(gaussian_reach(cloud, i, rule), extents[i], 1e-6) << i;
    EXPECT_NEAR(gaussian_reach(cloud, 4, rule), 0.08, 1e-7);
    EXPECT_EQ(stream_levels(cloud, rule), (std::vector<std::uint8_t>{1, 2, 3, 4, 2}));
    cloud.coverage_min[0] = -1.0f;  // no S_min: never too small
    EXPECT_TRUE(std::isinf(gaussian_reach(cloud, 0, rule)));
    cloud.coverage_min[0] = 100.0f;
    cloud.lod_level[0] = 4;  // the coarsest level: never too small
    EXPECT_TRUE(std::isinf(gaussian_reach(cloud, 0, rule)));
    cloud.opacity_logits[1] = -10.0f;  // never visible: extent 0
    EXPECT_EQ(gaussian_reach(cloud, 1, rule), 0.0);
    EXPECT_EQ(stream_order(cloud, rule), (std::vector<std::uint32_t>{0, 3, 2, 4, 1}));

    StreamLevelRule bad = rule;
    bad.reach_min = {0.1f, 0.2f, 0.05f};
    EXPECT_NE(check_stream_level_rule(bad).find("decrease"), std::string::npos);
    bad.reach_min = {0.4f, 0.12f, 0.0f};
    EXPECT_FALSE(check_stream_level_rule(bad).empty());
    EXPECT_TRUE(check_stream_level_rule(rule).empty());
}

TEST(WorldGenerator, SameSeedSameBytesForAnyThreadCountAndAnotherSeedDiffers) {
    const fs::path dir = engine::test::output_dir("world");
    fs::remove_all(dir);
    const WorldResult a = generate_world(tiny_options(dir / "a", 5, 2));
    generate_world(tiny_options(dir / "b", 5, 1));
    generate_world(tiny_options(dir / "c", 6, 2));
    EXPECT_FALSE(a.summary.cached);
    EXPECT_EQ(a.summary.chunks, 9u);
    EXPECT_GT(a.summary.gaussians, 1000u);
    EXPECT_GT(a.summary.props, 0u);
    const auto first = folder_bytes(dir / "a"), same = folder_bytes(dir / "b"), other = folder_bytes(dir / "c");
    EXPECT_EQ(first.size(), 1u + 9u + 4u + 5u);  // manifest, chunks, house/fence/post/terrain meshes, groups
    EXPECT_TRUE(first == same);
    EXPECT_NE(first.at("world.json"), other.at("world.json"));
    EXPECT_NE(first.at("gen-1/chunks/chunk_+000_+000.lod.ply"), other.at("gen-1/chunks/chunk_+000_+000.lod.ply"));
}

TEST(WorldGenerator, ManifestMatchesTheChunkFilesAndRangesReadExactlyTheirRecords) {
    const fs::path dir = engine::test::output_dir("world");
    fs::remove_all(dir);
    const WorldResult world = generate_world(tiny_options(dir, 9, 2));
    const WorldManifest m = read_world_manifest(dir / kManifestFileName);
    ASSERT_EQ(m.chunks.size(), 9u);
    std::uint64_t coarse = 0;
    for (const ChunkEntry& c : m.chunks) {
        const SplatCloud whole = load_splat_file(dir / c.file);
        ASSERT_EQ(whole.size(), c.prefix_count[0]);
        EXPECT_EQ(fs::file_size(dir / c.file), c.file_bytes);
        glm::vec3 lo(1e30f), hi(-1e30f);
        std::array<std::uint64_t, kLevels> counts{};
        std::array<double, kLevels> extent{};
        const std::vector<std::uint8_t> stream = stream_levels(whole, m.stream_levels);
        for (std::size_t i = 0; i < whole.size(); ++i) {
            lo = glm::min(lo, whole.positions[i]);
            hi = glm::max(hi, whole.positions[i]);
            for (int l = 1; l <= stream[i]; ++l) ++counts[static_cast<std::size_t>(l - 1)];
            if (i > 0) {
                EXPECT_LE(stream[i], stream[i - 1]) << "stream level 4 first";
            }
            // Every Gaussian of the coarsest bake level is in stream level 4 (always resident).
            if (whole.lod_level[i] == kLevels) {
                EXPECT_EQ(stream[i], kLevels);
            }
            auto& e = extent[static_cast<std::size_t>(stream[i] - 1)];
            e = std::max(e, gaussian_extent(whole.log_scales[i], whole.opacity_logits[i]));
        }
        EXPECT_EQ(counts, c.prefix_count);
        EXPECT_EQ(lo, c.bounds_min);
        EXPECT_EQ(hi, c.bounds_max);
        for (int l = 0; l < kLevels; ++l) EXPECT_GE(c.levels[l].extent_max, extent[l]);
        coarse += static_cast<std::uint64_t>(
            std::count_if(whole.lod_level.begin(), whole.lod_level.end(), [](std::uint8_t l) { return l >= 2; }));

        // Ranges: the coarse prefix, one level alone, and an arbitrary window.
        const auto [level2_begin, level2_end] = level_range(c, 2);
        const std::pair<std::uint64_t, std::uint64_t> ranges[] = {
            {0, c.prefix_count[1]}, {level2_begin, level2_end}, {c.prefix_count[0] / 3, c.prefix_count[0] / 3 + 17}, {0, 0}};
        for (const auto& [begin, end] : ranges) {
            const SplatCloud part = read_chunk_range(dir / c.file, c, begin, end);
            ASSERT_EQ(part.size(), end - begin);
            for (std::size_t i = 0; i < part.size(); ++i) expect_same_gaussian(part, i, whole, begin + i);
        }
    }
    EXPECT_GT(coarse, 0u) << "the bake made coarse levels";
    EXPECT_EQ(world.summary.gaussians, m.gaussians);
}

TEST(WorldGenerator, RangeReadsRefuseMismatchedFiles) {
    const fs::path dir = engine::test::output_dir("world");
    fs::remove_all(dir);
    const WorldManifest m = generate_world(tiny_options(dir, 3, 2)).manifest;
    const ChunkEntry& c = m.chunks[0];
    const fs::path file = dir / c.file;
    const auto n = c.prefix_count[0];
    EXPECT_NE(error_of([&] { read_chunk_range(file, c, 0, n + 1); }).find(file.string()), std::string::npos);
    EXPECT_NE(error_of([&] { read_chunk_range(dir / "chunks/none.ply", c, 0, 1); }).find("none.ply"), std::string::npos);
    ChunkEntry lying = c;
    lying.header_bytes += 1;
    lying.file_bytes += 1;
    EXPECT_NE(error_of([&] { read_chunk_range(file, lying, 0, 1); }).find(file.string()), std::string::npos);
    ChunkEntry unchecked = c;
    unchecked.record_crc32.pop_back();
    EXPECT_NE(error_of([&] { read_chunk_range(file, unchecked, 0, 1); }).find("record checksums"), std::string::npos);
    fs::resize_file(file, c.file_bytes - 10);  // truncated
    const std::string message = error_of([&] { read_chunk_range(file, c, 0, 1); });
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find("bytes"), std::string::npos) << message;
}

// A chunk file changed at the same size, so that size, header layout and values all still look
// right: the checksums must catch it, in the block that changed and only there.
TEST(WorldGenerator, RangeReadsRefuseAFileChangedAtTheSameSize) {
    const fs::path dir = engine::test::output_dir("world");
    fs::remove_all(dir);
    const WorldManifest m = generate_world(tiny_options(dir, 3, 2)).manifest;
    const auto biggest = std::max_element(m.chunks.begin(), m.chunks.end(),
                                          [](const ChunkEntry& a, const ChunkEntry& b) {
                                              return a.prefix_count[0] < b.prefix_count[0];
                                          });
    const ChunkEntry& c = *biggest;
    const fs::path file = dir / c.file;
    const std::vector<std::uint8_t> original = engine::read_binary_file(file);
    const auto blocks = record_blocks(c, 0, c.prefix_count[0]);
    ASSERT_GE(blocks.size(), 2u) << "the test needs a chunk of more than one block";
    // The stream level of the last record: the finest level the chunk has.
    int last_level = 1;
    while (level_range(c, last_level).first == level_range(c, last_level).second) ++last_level;
    const auto [last_begin, last_end] = level_range(c, last_level);

    // Flip the lowest mantissa bit of one float in the last record: still finite, same stream level.
    std::vector<std::uint8_t> flipped = original;
    const SplatCloud before = load_splat_file(file);
    flipped[c.header_bytes + (c.prefix_count[0] - 1) * c.vertex_bytes + 24] ^= 1u;  // f_dc_0 after x y z nx ny nz
    engine::write_file_atomic(file, flipped);
    const SplatCloud after = load_splat_file(file);  // the file reader sees nothing wrong
    ASSERT_EQ(after.size(), before.size());
    EXPECT_NE(after.sh_dc.back(), before.sh_dc.back()) << "the flip changed a colour that would be drawn";
    const std::string message = error_of([&] { read_chunk_range(file, c, last_begin, last_end); });
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find("checksum"), std::string::npos) << message;
    EXPECT_NE(message.find("[" + std::to_string(blocks.back().begin) + ", " + std::to_string(c.prefix_count[0]) + ")"),
              std::string::npos)
        << message;
    // A single record of that block fails too (the read is widened to the whole block); the blocks
    // before it still read: a bad block fails only the reads that need it.
    const std::string one = error_of([&] { read_chunk_range(file, c, blocks.back().begin, blocks.back().begin + 1); });
    EXPECT_NE(one.find("checksum"), std::string::npos) << one;
    EXPECT_EQ(read_chunk_range(file, c, 0, blocks.back().begin).size(), blocks.back().begin);

    // A header changed at the same size: two properties' names swapped.
    std::vector<std::uint8_t> swapped = original;
    std::string header(original.begin(), original.begin() + static_cast<std::ptrdiff_t>(c.header_bytes));
    const auto at0 = header.find("property float f_dc_0\n"), at1 = header.find("property float f_dc_1\n");
    ASSERT_NE(at0, std::string::npos);
    ASSERT_NE(at1, std::string::npos);
    std::swap(swapped[at0 + 20], swapped[at1 + 20]);
    engine::write_file_atomic(file, swapped);
    const std::string header_message = error_of([&] { read_chunk_range(file, c, 0, 1); });
    EXPECT_NE(header_message.find("header does not match the manifest's checksum"), std::string::npos)
        << header_message;

    engine::write_file_atomic(file, original);
    EXPECT_EQ(read_chunk_range(file, c, 0, c.prefix_count[0]).size(), c.prefix_count[0]);
}

TEST(WorldGenerator, SecondRunReusesTheCacheAndATruncatedChunkInvalidatesIt) {
    const fs::path dir = engine::test::output_dir("world");
    fs::remove_all(dir);
    const WorldOptions options = tiny_options(dir, 4, 2);
    generate_world(options);
    const auto bytes = folder_bytes(dir);
    std::map<std::string, fs::file_time_type> times;
    for (const auto& [name, content] : bytes) times[name] = fs::last_write_time(dir / name);

    const WorldResult again = generate_world(options);
    EXPECT_TRUE(again.summary.cached);
    for (const auto& [name, time] : times) EXPECT_EQ(fs::last_write_time(dir / name), time) << name << " was rewritten";

    WorldOptions denser = options;
    denser.density = 0.11f;
    std::string why;
    EXPECT_FALSE(find_cached_world(denser, &why));
    EXPECT_NE(why.find("density"), std::string::npos) << why;

    const fs::path chunk = dir / again.manifest.chunks[2].file;
    fs::resize_file(chunk, fs::file_size(chunk) - 1);
    EXPECT_FALSE(find_cached_world(options, &why));
    EXPECT_NE(why.find(chunk.filename().string()), std::string::npos) << why;
    const WorldResult regenerated = generate_world(options);
    EXPECT_FALSE(regenerated.summary.cached);
    // The same world in the next generation folder, the damaged one removed.
    EXPECT_TRUE(without_generation(folder_bytes(dir)) == without_generation(bytes));
    EXPECT_TRUE(fs::is_directory(dir / "gen-2"));
    EXPECT_FALSE(fs::exists(dir / "gen-1"));
}

TEST(WorldGenerator, PropMeshesLoadThroughTheEngineLoader) {
    const fs::path dir = engine::test::output_dir("world");
    write_prop_meshes(dir);
    write_terrain_mesh(dir, WorldTerrain(2, 128.0f));
    for (const char* mesh : {kHouseMesh, kFenceMesh, kPostMesh, kTerrainMesh}) {
        const engine::MeshAsset asset = engine::load_gltf(dir / mesh);
        EXPECT_GT(asset.triangle_count(), 10u) << mesh;
        EXPECT_FALSE(asset.materials.empty()) << mesh;
        for (const auto& primitive : asset.primitives)
            for (const auto& v : primitive.vertices) EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-3f) << mesh;
    }
    const engine::MeshAsset house = engine::load_gltf(dir / kHouseMesh);
    EXPECT_NEAR(house.bounds_max.y, 5.2f, 1e-4f);  // the chimney's top
    EXPECT_NEAR(house.bounds_min.y, 0.0f, 1e-6f);  // standing on its origin
    const engine::MeshAsset terrain = engine::load_gltf(dir / kTerrainMesh);
    EXPECT_NEAR(terrain.bounds_max.x - terrain.bounds_min.x, 128.0f, 1e-3f);
}

TEST(WorldGenerator, PropsStandOnTheGroundAndNothingButGroundIsInsideAHouse) {
    // The first seed whose 192 m world has a house (the layout alone is cheap).
    std::uint64_t seed = 1;
    for (; seed < 50; ++seed) {
        const WorldLayout layout = make_world_layout(WorldTerrain(seed, 192.0f), seed);
        if (std::any_of(layout.props.begin(), layout.props.end(), [](const Prop& p) { return p.mesh == kHouseMesh; })) break;
    }
    const WorldTerrain terrain(seed, 192.0f);
    const WorldLayout layout = make_world_layout(terrain, seed);
    const auto house = std::find_if(layout.props.begin(), layout.props.end(), [](const Prop& p) { return p.mesh == kHouseMesh; });
    ASSERT_NE(house, layout.props.end());
    for (const Prop& p : layout.props) {
        EXPECT_LT(std::abs(p.translation.x), 96.0f);
        EXPECT_LT(std::abs(p.translation.z), 96.0f);
        EXPECT_GT(terrain.river_distance(p.translation.x, p.translation.z), WorldTerrain::kRiverHalfWidth);
        EXPECT_NEAR(p.translation.y, terrain.height(p.translation.x, p.translation.z), p.mesh == kHouseMesh ? 2.5f : 1e-4f);
    }
    // The content of a 48 m square around the house at full density.
    ContentContext context{seed, 1.0f, &terrain, &layout, 99};
    const glm::vec2 centre(house->translation.x, house->translation.z);
    ContentCounts counts;
    const SplatCloud cloud = make_chunk_content(context, {centre - 24.0f, centre + 24.0f}, &counts);
    const double yaw = glm::radians(static_cast<double>(house->rotation_euler_deg.y));
    std::size_t inside = 0;
    for (const glm::vec3& p : cloud.positions) {
        // House-local x and z: the inverse yaw rotation.
        const double dx = p.x - centre.x, dz = p.z - centre.y;
        const double local_x = std::cos(yaw) * dx - std::sin(yaw) * dz, local_z = std::sin(yaw) * dx + std::cos(yaw) * dz;
        if (std::abs(local_x) > 3.0 || std::abs(local_z) > 2.5) continue;
        ++inside;
        EXPECT_LT(p.y - terrain.height(p.x, p.z), 0.5f) << "a Gaussian stands inside the house at " << p.x << ", " << p.z;
    }
    EXPECT_GT(inside, 10u) << "the ground under the house";
    EXPECT_GT(counts.ground, 1000u);
    EXPECT_GT(counts.fences, 100u) << "the garden's picket fence";
}
