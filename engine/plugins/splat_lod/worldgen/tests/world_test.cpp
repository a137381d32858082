// The sample world's manifest and chunks: the manifest (round trip, every kind of bad input, the
// writer's checks, the record blocks of its checksums), and describe_chunk's stream order and stream
// levels. Generated worlds: world_test_generator.cpp; failed, killed and concurrent runs:
// world_output_safety_test.cpp.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/stream_levels.h"
#include "splat_lod/core/world_manifest.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using namespace splat_lod;
using namespace splat_lod::world;
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
        if (k == 1) {  // a compressed chunk: its block sizes are in its file
            c.codec = ChunkCodec::compact;
            c.file = fs::path("chunks") / (c.id + ".splatc");
            c.header_bytes = 84;
            c.vertex_bytes = 0;
            c.file_bytes = 84 + 77000;
        }
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
        EXPECT_EQ(a.codec, b.codec);
        EXPECT_EQ(b.record_crc32.size(), k == 0 ? 8u : 5u)
            << "levels 4, 3, 2: one block each; level 1: 4960 records in 5 (PLY) or 2 (compressed)";
    }
    ASSERT_EQ(r.props.size(), 1u);
    EXPECT_EQ(r.props[0].mesh, m.props[0].mesh);
    EXPECT_EQ(r.props[0].translation, m.props[0].translation);
    EXPECT_EQ(r.props[0].rotation_euler_deg, m.props[0].rotation_euler_deg);
    EXPECT_EQ(r.props[0].scale, m.props[0].scale);
    EXPECT_EQ(chunk_id({3, -2}), "chunk_+003_-002");
    // The feature scale: left out where it is the size (and read back as the size), kept where less.
    EXPECT_EQ(r.feature_scale(), m.size_m);
    EXPECT_EQ(json::parse(engine::read_text_file(path)).count("feature_m"), 0u);
    WorldManifest larger = sample_manifest();
    larger.feature_m = 32.0f;
    write_world_manifest(path, larger);
    EXPECT_EQ(read_world_manifest(path).feature_scale(), 32.0f);
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
        {"reach_count",
         [](json& j) {
             j["stream_levels"]["reach_min"] = {0.4, 0.1};
         },
         "stream_levels.reach_min"},
        {"no_rule", [](json& j) { j.erase("stream_levels"); }, "stream_levels: missing"},
        {"unknown_top", [](json& j) { j["sizem"] = 3; }, "sizem: unknown key"},
        {"unknown_chunk", [](json& j) { j["chunks"][1]["colour"] = 1; }, "chunks[1].colour: unknown key"},
        {"missing", [](json& j) { j.erase("seed"); }, "seed: missing"},
        {"wrong_type", [](json& j) { j["size_m"] = "large"; }, "size_m"},
        {"negative_size", [](json& j) { j["chunk_size_m"] = -64; }, "chunk_size_m"},
        {"feature_zero", [](json& j) { j["feature_m"] = 0; }, "feature_m"},
        {"feature_larger", [](json& j) { j["feature_m"] = 256; }, "feature_m: is larger than size_m"},
        {"negative_count", [](json& j) { j["chunks"][0]["header_bytes"] = -1; }, "chunks[0].header_bytes"},
        {"nan", [](json& j) { j["chunks"][0]["bounds_min"][1] = nullptr; }, "chunks[0].bounds_min[1]"},
        {"nan_extent", [](json& j) { j["chunks"][0]["levels"][2]["extent_max"] = nullptr; },
         "chunks[0].levels[2].extent_max"},
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
        {"codec", [](json& j) { j["chunks"][0]["codec"] = "zip"; }, "chunks[0].codec"},
        {"compact_vertex_bytes", [](json& j) { j["chunks"][1]["vertex_bytes"] = 77; }, "chunks[1].vertex_bytes"},
        {"compact_file_bytes", [](json& j) { j["chunks"][1]["file_bytes"] = 10; }, "chunks[1].file_bytes"},
        {"compact_crc_count", [](json& j) { j["chunks"][1]["record_crc32"].erase(0); }, "blocks of up to 4096"},
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

// An import's quadtree: a chunk of span 1 covers 2 × 2 cells of a 4-cell grid. Its span survives the
// round trip (a chunk of span 0 writes none), and a span that is misaligned, leaves the grid, overlaps
// another chunk or is out of range is refused naming the chunk.
// Worlds of version 4 (every chunk a PLY file, no "codec" key) still read, as PLY chunks, and keep the
// checksum their cached references are found by when written again as version 5.
TEST(WorldManifest, Version4ManifestsReadAsPlyChunks) {
    const fs::path dir = engine::test::output_dir("world");
    WorldManifest m = sample_manifest();
    m.chunks.pop_back();  // the compressed one
    m.gaussians = m.chunks[0].prefix_count[0];
    write_world_manifest(dir / "v5.json", m);
    json old = json::parse(engine::read_text_file(dir / "v5.json"));
    EXPECT_FALSE(old["chunks"][0].contains("codec")) << "PLY chunks are written as version 4 wrote them";
    old["version"] = 4;
    engine::write_text_file_atomic(dir / "v4.json", old.dump());
    const WorldManifest r = read_world_manifest(dir / "v4.json");
    EXPECT_EQ(r.version, 4);
    EXPECT_EQ(r.chunks[0].codec, ChunkCodec::ply);
    EXPECT_EQ(chunks_checksum(r), chunks_checksum(m));
    write_world_manifest(dir / "again.json", r);
    EXPECT_EQ(read_world_manifest(dir / "again.json").version, kManifestVersion);
}

TEST(WorldManifest, ChunksOfSeveralCellsAreAlignedInsideTheGridAndApart) {
    const fs::path dir = engine::test::output_dir("world");
    WorldManifest m = sample_manifest();
    m.size_m = 256.0f;
    m.chunks[0].cell = {-2, -2};
    m.chunks[0].id = chunk_id(m.chunks[0].cell);
    m.chunks[0].span = 1;
    m.chunks[1].cell = {0, 0};
    m.chunks[1].id = chunk_id(m.chunks[1].cell);
    write_world_manifest(dir / "spans.json", m);
    const WorldManifest r = read_world_manifest(dir / "spans.json");
    EXPECT_EQ(r.chunks[0].span, 1);
    EXPECT_EQ(r.chunks[1].span, 0);
    const json good = json::parse(engine::read_text_file(dir / "spans.json"));
    EXPECT_FALSE(good["chunks"][1].contains("span"));
    const std::vector<std::pair<std::function<void(json&)>, std::string>> cases = {
        {[](json& j) {
             j["chunks"][0]["cell"] = {-1, -2};
         },
         "chunks[0].cell: a chunk of span 1 must start"},
        {[](json& j) { j["chunks"][1]["span"] = 2; }, "chunks[1].cell: a chunk of span 2"},
        {[](json& j) {
             j["chunks"][1]["cell"] = {-1, -1};
         },
         "chunks[1].cell: overlaps an earlier chunk"},
        {[](json& j) { j["chunks"][0]["span"] = 11; }, "chunks[0].span: must be 0 to 10"},
    };
    for (const auto& [mutate, expected] : cases) {
        json document = good;
        mutate(document);
        engine::write_text_file_atomic(dir / "bad_span.json", document.dump());
        const std::string message = error_of([&] { read_world_manifest(dir / "bad_span.json"); });
        EXPECT_NE(message.find(expected), std::string::npos) << message;
    }
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
