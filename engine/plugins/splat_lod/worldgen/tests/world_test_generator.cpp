// Tiny generated sample worlds: same seed → same bytes for any thread count, the manifest against
// the chunk files and read_chunk_range against whole-file loads, range reads that refuse changed
// files, the cache and its invalidation, props that the engine's glTF loader loads, and nothing but
// ground inside a house. The manifest alone: world_test.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "chunk_content.h"
#include "engine/assets/mesh_asset.h"
#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/gaussian_extent.h"
#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/stream_levels.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/synth/world_terrain.h"
#include "splat_lod/worldgen/world_generator.h"
#include "splat_lod/worldgen/world_meshes.h"
#include "test_support.h"
#include "tiny_world.h"
#include "world_layout.h"

namespace {

namespace fs = std::filesystem;
using namespace splat_lod;
using namespace splat_lod::world;
using engine::test::folder_bytes;
using engine::test::without_generation;

using splat_io_test::error_of;  // the engine::Error message, "" when none

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
    EXPECT_NE(first.at("gen-1/chunks/chunk_+000_+000.splatc"), other.at("gen-1/chunks/chunk_+000_+000.splatc"));
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
        std::array<double, kLevels> extent{};
        // The stream level each record is filed under (its range in the file) and the one its values
        // give: the same but for records the compressed file moved across a level's boundary when it
        // quantised them (2.5% of one tiny chunk's, those within a scale step of a boundary), which
        // must stay rare; the level's bounds still hold for them (below), which is what streaming uses.
        const std::vector<std::uint8_t> stream = stream_levels(whole, m.stream_levels);
        std::size_t moved = 0;
        for (int level = kLevels; level >= 1; --level) {
            const auto [begin, end] = level_range(c, level);
            for (std::uint64_t i = begin; i < end; ++i) {
                lo = glm::min(lo, whole.positions[i]);
                hi = glm::max(hi, whole.positions[i]);
                moved += stream[i] != level;
                // Every Gaussian of the coarsest bake level is in stream level 4 (always resident).
                if (whole.lod_level[i] == kLevels) {
                    EXPECT_EQ(level, kLevels);
                }
                auto& e = extent[static_cast<std::size_t>(level - 1)];
                e = std::max(e, gaussian_extent(whole.log_scales[i], whole.opacity_logits[i]));
            }
        }
        EXPECT_LE(moved, whole.size() / 20) << c.id;
        // The bounds hold the means as the file gives them back and as they were baked (the compressed
        // file quantises them by well under a millimetre).
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(lo[a], c.bounds_min[a]);
            EXPECT_LE(hi[a], c.bounds_max[a]);
            EXPECT_NEAR(lo[a], c.bounds_min[a], 1e-3f);
            EXPECT_NEAR(hi[a], c.bounds_max[a], 1e-3f);
        }
        for (int l = 0; l < kLevels; ++l) EXPECT_GE(c.levels[l].extent_max, extent[l]);
        coarse += static_cast<std::uint64_t>(
            std::count_if(whole.lod_level.begin(), whole.lod_level.end(), [](std::uint8_t l) { return l >= 2; }));

        // Ranges: the coarse prefix, one level alone, and an arbitrary window.
        const auto [level2_begin, level2_end] = level_range(c, 2);
        const std::pair<std::uint64_t, std::uint64_t> ranges[] = {{0, c.prefix_count[1]},
                                                                  {level2_begin, level2_end},
                                                                  {c.prefix_count[0] / 3, c.prefix_count[0] / 3 + 17},
                                                                  {0, 0}};
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
    EXPECT_NE(error_of([&] { read_chunk_range(dir / "chunks/none.ply", c, 0, 1); }).find("none.ply"),
              std::string::npos);
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
// right: the checksums must catch it, in the block that changed and only there. PLY chunks (worlds of
// manifest version 4 and --chunk-codec ply); compact_chunk_test.cpp damages compressed ones.
TEST(WorldGenerator, RangeReadsRefuseAFileChangedAtTheSameSize) {
    const fs::path dir = engine::test::output_dir("world");
    fs::remove_all(dir);
    WorldOptions options = tiny_options(dir, 3, 2);
    options.chunk_codec = ChunkCodec::ply;
    const WorldManifest m = generate_world(options).manifest;
    const auto biggest = std::max_element(
        m.chunks.begin(), m.chunks.end(),
        [](const ChunkEntry& a, const ChunkEntry& b) { return a.prefix_count[0] < b.prefix_count[0]; });
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
    write_terrain_mesh(dir, WorldTerrain(2, 128.0f, 128.0f));
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
        const WorldLayout layout = make_world_layout(WorldTerrain(seed, 192.0f, 192.0f), seed);
        if (std::any_of(layout.props.begin(), layout.props.end(), [](const Prop& p) { return p.mesh == kHouseMesh; }))
            break;
    }
    const WorldTerrain terrain(seed, 192.0f, 192.0f);
    const WorldLayout layout = make_world_layout(terrain, seed);
    const auto house =
        std::find_if(layout.props.begin(), layout.props.end(), [](const Prop& p) { return p.mesh == kHouseMesh; });
    ASSERT_NE(house, layout.props.end());
    for (const Prop& p : layout.props) {
        EXPECT_LT(std::abs(p.translation.x), 96.0f);
        EXPECT_LT(std::abs(p.translation.z), 96.0f);
        EXPECT_GT(terrain.river_distance(p.translation.x, p.translation.z), WorldTerrain::kRiverHalfWidth);
        EXPECT_NEAR(p.translation.y, terrain.height(p.translation.x, p.translation.z),
                    p.mesh == kHouseMesh ? 2.5f : 1e-4f);
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
        const double local_x = std::cos(yaw) * dx - std::sin(yaw) * dz,
                     local_z = std::sin(yaw) * dx + std::cos(yaw) * dz;
        if (std::abs(local_x) > 3.0 || std::abs(local_z) > 2.5) continue;
        ++inside;
        EXPECT_LT(p.y - terrain.height(p.x, p.z), 0.5f)
            << "a Gaussian stands inside the house at " << p.x << ", " << p.z;
    }
    EXPECT_GT(inside, 10u) << "the ground under the house";
    EXPECT_GT(counts.ground, 1000u);
    EXPECT_GT(counts.fences, 100u) << "the garden's picket fence";
}

// A world larger than the largest feature scale is the world of its middle with more land around it:
// the same ground and the same props inside the middle square (but at its east end, where the larger
// world's props go on), props beyond it on both sides, and a generator string that says so.
TEST(WorldGenerator, ALargerWorldKeepsTheWorldOfItsMiddle) {
    constexpr std::uint64_t seed = 7;
    const float middle = WorldTerrain::kFeatureScaleMax, size = 2.0f * middle;
    EXPECT_EQ(WorldTerrain::feature_scale_for(size), middle);
    EXPECT_EQ(WorldTerrain::feature_scale_for(256.0f), 256.0f);
    const WorldTerrain small(seed, middle, middle), large(seed, size, middle);
    for (float z = -0.5f * middle; z <= 0.5f * middle; z += 37.0f)
        for (float x = -0.5f * middle; x <= 0.5f * middle; x += 41.0f) {
            ASSERT_EQ(small.height(x, z), large.height(x, z)) << x << ", " << z;
            ASSERT_EQ(small.forest(x, z), large.forest(x, z)) << x << ", " << z;
            ASSERT_EQ(small.path_z(x), large.path_z(x)) << x;
        }
    const auto props_between = [](const WorldLayout& layout, float from, float to) {
        std::vector<Prop> props;
        for (const Prop& p : layout.props)
            if (p.translation.x >= from && p.translation.x < to) props.push_back(p);
        return props;
    };
    const WorldLayout a = make_world_layout(small, seed), b = make_world_layout(large, seed);
    const float east = 0.5f * middle - 60.0f;  // clear of the props the larger world adds past the end
    const std::vector<Prop> pa = props_between(a, -0.5f * middle, east), pb = props_between(b, -0.5f * middle, east);
    ASSERT_EQ(pa.size(), pb.size());
    EXPECT_GT(pa.size(), 20u);
    for (std::size_t k = 0; k < pa.size(); ++k) {
        EXPECT_EQ(pa[k].mesh, pb[k].mesh) << k;
        EXPECT_EQ(pa[k].translation, pb[k].translation) << k;
        EXPECT_EQ(pa[k].rotation_euler_deg, pb[k].rotation_euler_deg) << k;
    }
    EXPECT_GT(props_between(b, -0.5f * size, -0.5f * middle).size(), 10u);  // the west
    EXPECT_GT(props_between(b, 0.5f * middle, 0.5f * size).size(), 10u);    // the east
    WorldOptions o;
    o.size_m = size;
    EXPECT_NE(generator_settings(o).find("; features 1024 m"), std::string::npos) << generator_settings(o);
    o.size_m = middle;
    EXPECT_EQ(generator_settings(o).find("features"), std::string::npos) << generator_settings(o);
}
