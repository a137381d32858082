// The walkthrough on any world: an imported world's ground (its manifest's ground grid, a walk through its
// densest chunk at its scale), the generated world's path unchanged, and path files (poses as given, keys
// sampled, every bad entry named).
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "sample_game/path_file.h"
#include "sample_game/world_ground.h"
#include "sample_game/world_path.h"
#include "splat_io_test_helpers.h"
#include "test_support.h"

namespace sw = splat_lod::world;
using sample_game::PathPose;
using sample_game::Segment;

using splat_io_test::error_of;

namespace {

// A 64-unit imported world of 16-unit chunks whose chunk (1, −1) holds the most Gaussians, its ground
// sloping up along x.
sw::WorldManifest imported_manifest() {
    sw::WorldManifest m;
    m.size_m = 64.0f;
    m.chunk_size_m = 16.0f;
    m.ground.cells = 4;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) m.ground.heights.push_back(static_cast<float>(i));
    for (const glm::ivec2 cell : {glm::ivec2(-1, 0), glm::ivec2(1, -1), glm::ivec2(0, 1)}) {
        sw::ChunkEntry c;
        c.cell = cell;
        c.prefix_count[0] = cell == glm::ivec2(1, -1) ? 900 : 100;
        m.chunks.push_back(c);
    }
    return m;
}

TEST(WorldGround, AnImportedWorldIsWalkedThroughItsDensestChunkAtItsScale) {
    const sample_game::WorldGround ground = sample_game::WorldGround::of(imported_manifest());
    EXPECT_TRUE(ground.imported());
    EXPECT_FLOAT_EQ(ground.scale(), 0.25f);
    EXPECT_FLOAT_EQ(ground.path_z(-20.0f), -8.0f) << "the middle of the densest chunk's row";
    EXPECT_FLOAT_EQ(ground.height(-30.0f, 0.0f), 0.0f);
    EXPECT_FLOAT_EQ(ground.height(30.0f, 0.0f), 3.0f);
    const auto poses = sample_game::sample_world_path(ground, 100);
    const auto shape = sample_game::path_shape_for(ground);
    EXPECT_FLOAT_EQ(shape.eye_height_m, std::max(1.7f * 0.25f, 0.005f * 64.0f));
    for (const PathPose& p : poses) {
        if (p.segment != Segment::ground) continue;
        EXPECT_FLOAT_EQ(p.eye.y, ground.height(p.eye.x, p.eye.z) + shape.eye_height_m);
        EXPECT_NEAR(p.eye.z, -8.0f, 1e-3f);
        EXPECT_GE(p.eye.x, -32.0f);
        EXPECT_LE(p.eye.x, 32.0f);
    }
}

TEST(WorldGround, AGeneratedWorldKeepsItsTerrainPath) {
    const sw::WorldTerrain terrain(3, 256.0f, 256.0f);
    sw::WorldManifest m;
    m.seed = 3;
    m.size_m = 256.0f;
    const auto from_manifest = sample_game::sample_world_path(sample_game::WorldGround::of(m), 50);
    const auto from_terrain = sample_game::sample_world_path(terrain, 50);
    ASSERT_EQ(from_manifest.size(), from_terrain.size());
    for (std::size_t i = 0; i < from_terrain.size(); ++i) EXPECT_EQ(from_manifest[i].eye, from_terrain[i].eye);
    EXPECT_FLOAT_EQ(from_terrain[0].eye.y, terrain.height(from_terrain[0].eye.x, from_terrain[0].eye.z) + 1.7f);
}

// A world larger than its feature scale is walked where the world of its middle is: the same start
// and the same ground frames (the flyout, the overview and the return grow with the world).
TEST(WorldGround, ALargerWorldIsWalkedWhereItsMiddleIs) {
    const float middle = sw::WorldTerrain::kFeatureScaleMax;
    const sw::WorldTerrain small(5, middle, middle), large(5, 3.0f * middle, middle);
    EXPECT_EQ(sample_game::WorldGround(small).walk_start(), sample_game::WorldGround(large).walk_start());
    const auto a = sample_game::sample_world_path(small, 100), b = sample_game::sample_world_path(large, 100);
    ASSERT_EQ(a.size(), b.size());
    int ground = 0;
    for (std::size_t i = 0; i < a.size() && a[i].segment == sample_game::Segment::ground; ++i, ++ground) {
        EXPECT_EQ(a[i].eye, b[i].eye) << i;
        EXPECT_EQ(b[i].segment, sample_game::Segment::ground) << i;
    }
    EXPECT_GT(ground, 10);
    sw::WorldManifest m;
    m.seed = 5;
    m.size_m = 3.0f * middle;
    m.feature_m = middle;  // what the generator writes for such a world
    EXPECT_EQ(sample_game::WorldGround::of(m).walk_start(), sample_game::WorldGround(large).walk_start());
}

TEST(PathFile, PosesAreTakenAsGivenKeysAreSampledAndBadEntriesNamed) {
    const auto dir = engine::test::output_dir("path_file");
    const sw::WorldTerrain terrain(5, 128.0f, 128.0f);
    const auto poses = sample_game::sample_world_path(terrain, 40);
    sample_game::write_path_file(dir / "poses.json", poses);
    const auto back = sample_game::read_path_file(dir / "poses.json", 999);
    ASSERT_EQ(back.size(), poses.size()) << "poses: their own count";
    for (std::size_t i = 0; i < poses.size(); ++i) {
        EXPECT_EQ(back[i].eye, poses[i].eye);
        EXPECT_EQ(back[i].segment, poses[i].segment);
    }
    std::ofstream(dir / "keys.json") << R"([{"eye": [0, 5, 0], "look": [1, 0, 0], "segment": "ground"},
        {"eye": [10, 5, 0], "look": [1, 0, 0], "segment": "overview"},
        {"eye": [20, 9, 0], "look": [1, -1, 0], "segment": "return"}])";
    const auto keyed = sample_game::read_path_file(dir / "keys.json", 30);
    ASSERT_EQ(keyed.size(), 30u);
    EXPECT_EQ(keyed.front().eye, glm::vec3(0.0f, 5.0f, 0.0f));
    const auto expect_error = [&](const std::string& text, const std::string& wanted) {
        std::ofstream(dir / "bad.json") << text;
        const std::string message = error_of([&] { sample_game::read_path_file(dir / "bad.json", 10); });
        EXPECT_NE(message.find("bad.json"), std::string::npos) << message;
        EXPECT_NE(message.find(wanted), std::string::npos) << message;
    };
    expect_error("[{", "JSON");
    expect_error(R"([{"eye": [0, 0, 0], "forward": [1, 0, 0], "segment": "ground"}])", "at least two");
    expect_error(R"([{"eye": [0, 0], "forward": [1, 0, 0], "segment": "ground"},
                     {"eye": [0, 0, 1], "forward": [1, 0, 0], "segment": "ground"}])",
                 "[0].eye");
    expect_error(R"([{"eye": [0, 0, 0], "forward": [1, 0, 0], "segment": "walk"},
                     {"eye": [0, 0, 1], "forward": [1, 0, 0], "segment": "ground"}])",
                 "\"walk\"");
    expect_error(R"([{"eye": [0, 0, 0], "forward": [1, 0, 0], "segment": "ground"},
                     {"eye": [0, 0, 1], "look": [1, 0, 0], "segment": "ground"}])",
                 "mixes");
    expect_error(R"([{"eye": [0, 0, 0], "forward": [0, 0, 0], "segment": "ground"},
                     {"eye": [0, 0, 1], "forward": [1, 0, 0], "segment": "ground"}])",
                 "zero");
}

}  // namespace
