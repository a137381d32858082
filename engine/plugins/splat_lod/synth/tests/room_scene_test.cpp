// The forward-facing room: reproducible bytes, the documented size, everything inside the room, and
// its capture grid and held-out views (in the capture's neighbourhood, never on the grid, and read
// back from the camera-path JSON it writes).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "engine/core/error.h"
#include "splat_lod/core/camera_set.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/synth/fine_detail_scene.h"
#include "splat_lod/synth/room_scene.h"
#include "test_support.h"

using splat_lod::SplatCloud;
namespace synth = splat_lod::synth;

namespace {

const SplatCloud& full_room() {
    static const SplatCloud cloud = synth::make_room_scene({});
    return cloud;
}

std::vector<char> file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(RoomScene, SameSeedWritesIdenticalBytesAndAnotherSeedDiffers) {
    const auto dir = engine::test::output_dir("synth");
    const synth::RoomOptions options{7, 0.2f};
    splat_lod::write_inria_ply(dir / "room_first.ply", synth::make_room_scene(options));
    splat_lod::write_inria_ply(dir / "room_second.ply", synth::make_room_scene(options));
    splat_lod::write_inria_ply(dir / "room_other_seed.ply", synth::make_room_scene({8, 0.2f}));
    const auto first = file_bytes(dir / "room_first.ply");
    ASSERT_GT(first.size(), 1000u);
    EXPECT_TRUE(first == file_bytes(dir / "room_second.ply"));
    EXPECT_FALSE(first == file_bytes(dir / "room_other_seed.ply"));
}

TEST(RoomScene, CountIsInTheDocumentedRangeAndFollowsDetail) {
    const std::size_t full = full_room().size();
    EXPECT_GE(full, synth::kRoomGaussiansMin);
    EXPECT_LE(full, synth::kRoomGaussiansMax);
    const std::size_t half = synth::make_room_scene({1, 0.5f}).size();
    EXPECT_NEAR(static_cast<double>(half) / static_cast<double>(full), 0.5, 0.1);
    EXPECT_THROW(synth::make_room_scene({1, 0.0f}), engine::Error);
    EXPECT_THROW(synth::make_room_scene({1, synth::kMaxDetail * 2.0f}), engine::Error);
}

TEST(RoomScene, EveryGaussianIsFiniteSmallAndInsideTheRoom) {
    const SplatCloud& cloud = full_room();
    ASSERT_NO_THROW(cloud.check_consistent());
    EXPECT_EQ(cloud.sh_degree, 0);
    EXPECT_FALSE(cloud.has_lod_attributes());
    std::size_t failures = 0;
    for (std::size_t i = 0; i < cloud.size() && failures < 10; ++i) {
        const glm::vec3 p = cloud.positions[i];
        const float largest = std::exp(std::max({cloud.log_scales[i].x, cloud.log_scales[i].y, cloud.log_scales[i].z}));
        const bool inside = std::abs(p.x) <= synth::kRoomHalfWidth + 0.01f && p.y >= -0.01f &&
                            p.y <= synth::kRoomHeight + 0.01f && p.z >= synth::kRoomFarZ - 0.01f &&
                            p.z <= synth::kRoomOpenZ + 0.01f;
        // Tiles are 1.5–10 cm apart: fine texture, nothing large.
        const bool ok = inside && std::isfinite(largest) && largest <= 0.07f && std::isfinite(cloud.opacity_logits[i]);
        if (!ok) {
            ADD_FAILURE() << "Gaussian " << i << " at (" << p.x << ", " << p.y << ", " << p.z << "), largest scale "
                          << largest;
            ++failures;
        }
    }
}

TEST(RoomCameras, TheCaptureIsAGridInASmallBoxLookingIntoTheRoom) {
    const auto grid = synth::room_capture_cameras();
    ASSERT_EQ(grid.size(), 24u);
    for (const auto& pose : grid) {
        EXPECT_LE(std::abs(pose.eye.x), 1.0f + 1e-5f) << pose.name;
        EXPECT_GE(pose.eye.y, 1.3f - 1e-5f);
        EXPECT_LE(pose.eye.y, 1.7f + 1e-5f);
        EXPECT_GE(pose.eye.z, 0.4f - 1e-5f);
        EXPECT_LE(pose.eye.z, 0.8f + 1e-5f);
        EXPECT_LT(pose.forward.z, -0.98f) << pose.name;  // within about 11° of −z
        EXPECT_NEAR(glm::dot(pose.forward, pose.up), 0.0f, 1e-5f);
        EXPECT_GT(pose.up.y, 0.9f);
    }
    EXPECT_EQ(synth::room_capture_cameras(3, 2).size(), 6u);
    EXPECT_THROW(synth::room_capture_cameras(0, 4), engine::Error);
    EXPECT_THROW(synth::room_capture_cameras(4, 65), engine::Error);
}

TEST(RoomCameras, HeldOutViewsAreNearTheCaptureButNotOnItsGrid) {
    const auto grid = synth::room_capture_cameras();
    const auto held_out = synth::room_held_out_cameras();
    ASSERT_EQ(held_out.size(), 8u);
    for (const auto& pose : held_out) {
        float nearest = 1e9f;
        for (const auto& g : grid) nearest = std::min(nearest, glm::length(pose.eye - g.eye));
        EXPECT_GT(nearest, 0.05f) << pose.name;
        EXPECT_LT(nearest, 2.5f) << pose.name;
        EXPECT_LT(pose.forward.z, -0.8f) << pose.name;  // still looking into the room
    }
}

TEST(RoomCameras, CameraPathJsonReadsBackAsTheSamePoses) {
    const auto held_out = synth::room_held_out_cameras();
    const auto read = splat_lod::eval::parse_camera_path(synth::camera_path_json(held_out), "held_out.json");
    ASSERT_EQ(read.size(), held_out.size());
    for (std::size_t i = 0; i < read.size(); ++i) {
        EXPECT_EQ(read[i].name, held_out[i].name);
        EXPECT_NEAR(glm::length(read[i].eye - held_out[i].eye), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::length(read[i].forward - held_out[i].forward), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::length(read[i].up - held_out[i].up), 0.0f, 1e-4f);
        EXPECT_NEAR(read[i].fov_y, held_out[i].fov_y, 1e-6f);
        EXPECT_NEAR(read[i].focus_distance, held_out[i].focus_distance, 1e-4f);
    }
}
