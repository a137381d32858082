// The walkthrough's camera path: the spline through its keys, even arc-length steps within each
// segment, every segment present in order, the walk on the ground and the flight above it, for
// several seeds and world sizes (the path is derived from the terrain alone).
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "sample_game/camera_path.h"
#include "sample_game/world_path.h"
#include "splat_lod/synth/world_terrain.h"

using sample_game::CameraPath;
using sample_game::PathKey;
using sample_game::PathPose;
using sample_game::Segment;
using splat_lod::world::WorldTerrain;

namespace {

std::vector<PathKey> zigzag() {
    return {{{0, 0, 0}, {1, 0, 0}, Segment::ground},
            {{1, 0, 0}, {1, 0, 0}, Segment::ground},
            {{3, 0, 1}, {1, 0, 1}, Segment::canopy},
            {{30, 10, 1}, {1, -1, 0}, Segment::overview},
            {{60, 10, 30}, {0, -1, 1}, Segment::return_to_ground},
            {{70, 2, 40}, {1, 0, 1}, Segment::return_to_ground}};  // the last key's segment names no span
}

struct WorldCase {
    std::uint64_t seed;
    float size;
};

class WorldPath : public ::testing::TestWithParam<WorldCase> {};

}  // namespace

TEST(CameraPath, PassesThroughItsKeysWithUnitDirections) {
    const CameraPath path(zigzag());
    for (std::size_t i = 0; i < path.keys().size(); ++i) {
        const PathPose pose = path.at(static_cast<float>(i));
        EXPECT_NEAR(glm::distance(pose.eye, path.keys()[i].eye), 0.0f, 1e-4f) << "key " << i;
        EXPECT_NEAR(glm::length(pose.forward), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(pose.forward, path.keys()[i].look), 1.0f, 1e-4f) << "key " << i;
    }
}

TEST(CameraPath, IsContinuousAndTurnsSmoothly) {
    const CameraPath path(zigzag());
    const int steps = 4000;
    PathPose previous = path.at(0.0f);
    float largest_step = 0.0f, largest_turn = 0.0f;
    for (int k = 1; k <= steps; ++k) {
        const PathPose pose = path.at(static_cast<float>(path.spans()) * static_cast<float>(k) / steps);
        largest_step = std::max(largest_step, glm::distance(pose.eye, previous.eye));
        largest_turn = std::max(largest_turn, std::acos(std::min(1.0f, glm::dot(pose.forward, previous.forward))));
        previous = pose;
    }
    // Centripetal Catmull-Rom: no jumps, loops or cusps; the longest span is ~42 m over 1000 steps.
    EXPECT_LT(largest_step, 0.2f);
    EXPECT_LT(largest_turn, 0.02f);  // radians per step
}

TEST(CameraPath, SamplesSegmentsInOrderAtEvenArcLengthSteps) {
    const CameraPath path(zigzag());
    const std::array<float, sample_game::kSegmentCount> shares{0.3f, 0.2f, 0.0f, 0.3f, 0.2f};
    const std::vector<PathPose> poses = path.sample(100, shares);
    ASSERT_EQ(poses.size(), 100u);
    EXPECT_NEAR(glm::distance(poses.front().eye, path.keys().front().eye), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::distance(poses.back().eye, path.keys().back().eye), 0.0f, 1e-3f);
    EXPECT_FLOAT_EQ(poses.front().t, 0.0f);
    EXPECT_FLOAT_EQ(poses.back().t, 1.0f);
    // The segments visited (ground, canopy, overview, return) get their shares of the frames.
    int counts[sample_game::kSegmentCount] = {};
    for (std::size_t i = 0; i < poses.size(); ++i) {
        ++counts[static_cast<int>(poses[i].segment)];
        if (i > 0) {
            EXPECT_GE(poses[i].segment, poses[i - 1].segment) << "frame " << i;
        }
    }
    EXPECT_EQ(counts[0], 30);
    EXPECT_EQ(counts[1], 20);
    EXPECT_EQ(counts[2], 0);
    EXPECT_EQ(counts[3], 30);
    EXPECT_EQ(counts[4], 20);
    // Within a segment, consecutive poses are the same distance apart (up to the arc table's accuracy).
    for (std::size_t i = 2; i < poses.size(); ++i) {
        if (poses[i].segment != poses[i - 1].segment || poses[i - 1].segment != poses[i - 2].segment) continue;
        const float a = glm::distance(poses[i].eye, poses[i - 1].eye),
                    b = glm::distance(poses[i - 1].eye, poses[i - 2].eye);
        EXPECT_NEAR(a, b, 0.02f * std::max(a, b) + 1e-4f)
            << "frame " << i << " (" << to_string(poses[i].segment) << ")";
    }
}

TEST(CameraPath, RejectsKeysItCannotUse) {
    auto message = [](std::vector<PathKey> keys) {
        try {
            CameraPath path(std::move(keys));
        } catch (const engine::Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({{{0, 0, 0}}}).find("at least two keys"), std::string::npos);
    EXPECT_NE(message({{{0, 0, 0}}, {{0, 0, 0}}}).find("key 1: the eye repeats"), std::string::npos);
    EXPECT_NE(message({{{0, 0, 0}, {0, 0, 0}}, {{1, 0, 0}}}).find("key 0: the look direction"), std::string::npos);
    EXPECT_NE(message({{{0, 0, 0}, {1, 0, 0}, Segment::overview}, {{1, 0, 0}, {1, 0, 0}, Segment::ground}})
                  .find("key 1: segments must not go back"),
              std::string::npos);
    EXPECT_THROW(CameraPath(zigzag()).sample(3, sample_game::kDefaultSegmentShares), engine::Error);
}

TEST_P(WorldPath, WalksOnTheGroundFliesOverItAndComesBack) {
    const WorldCase c = GetParam();
    const WorldTerrain terrain(c.seed, c.size, WorldTerrain::feature_scale_for(c.size));
    const sample_game::WorldPathShape shape;
    const std::vector<PathPose> poses = sample_game::sample_world_path(terrain, 300, shape);
    ASSERT_EQ(poses.size(), 300u);
    std::array<int, sample_game::kSegmentCount> frames{};
    std::array<float, sample_game::kSegmentCount> highest{}, lowest{};
    lowest.fill(1e9f);
    const glm::vec3 centre = sample_game::world_centre(terrain);
    for (const PathPose& pose : poses) {
        const auto k = static_cast<std::size_t>(pose.segment);
        const float above = pose.eye.y - terrain.height(pose.eye.x, pose.eye.z);
        ++frames[k];
        highest[k] = std::max(highest[k], above);
        lowest[k] = std::min(lowest[k], above);
        EXPECT_GE(above, shape.min_clearance_m - 1e-3f);
        EXPECT_LE(std::abs(pose.eye.x), 0.75f * c.size);
        EXPECT_LE(std::abs(pose.eye.z), 0.75f * c.size);
        if (pose.segment == Segment::overview) {  // looking at the centre of the world
            EXPECT_GT(glm::dot(pose.forward, glm::normalize(centre - pose.eye)), 0.98f);
        }
        if (pose.segment == Segment::ground) {  // walking: never under water
            EXPECT_GT(terrain.river_distance(pose.eye.x, pose.eye.z), WorldTerrain::kRiverHalfWidth);
        }
    }
    for (std::size_t k = 0; k < sample_game::kSegmentCount; ++k)
        EXPECT_GT(frames[k], 20) << sample_game::kSegmentNames[k];
    EXPECT_NEAR(lowest[0], shape.eye_height_m, 0.3f);
    EXPECT_NEAR(highest[0], shape.eye_height_m, 0.3f);
    EXPECT_NEAR(highest[1], shape.canopy_height_m, 1.5f);
    EXPECT_GT(lowest[3], 0.3f * c.size);  // the overview is high above the whole world
    EXPECT_NEAR(glm::distance(poses.back().eye, poses.front().eye), 0.0f, 0.05f) << "the walkthrough loops";
}

INSTANTIATE_TEST_SUITE_P(SeedsAndSizes, WorldPath,
                         ::testing::Values(WorldCase{1, 1024.0f}, WorldCase{7, 1024.0f}, WorldCase{1, 256.0f},
                                           WorldCase{11, 96.0f}, WorldCase{3, 128.0f}),
                         [](const auto& test) {
                             return "seed" + std::to_string(test.param.seed) + "_size" +
                                    std::to_string(static_cast<int>(test.param.size));
                         });
