#pragma once
// Internal to the world generator: the bake cameras of a chunk. A chunk is seen by a player walking
// or flying through the world, from inside it out to the far distance, so its coverage ranges and
// the refinement should come from such views (docs/algorithms.md §4: coverage ranges measured from
// the directions users view from are the ones that hold), not from an object orbit: three rings of views aimed at the
// chunk's middle, at eye height just outside it, low flight a few chunks away, and high above far away.
#include <functional>
#include <vector>

#include "chunk_content.h"
#include "splat_lod/core/camera_set.h"
#include "splat_lod/synth/world_terrain.h"

namespace splat_lod::world {

inline constexpr int kChunkCameraRings = 3;
inline constexpr int kChunkCamerasPerRing = 8;
inline constexpr float kChunkCameraFovDeg = 60.0f;

// A ring of views: eyes at `distance` half-diagonals from the chunk's middle, `height` world units
// (times the scale) plus `height_per_half_diagonal` half-diagonals above the ground under the eye.
struct ChunkCameraRing {
    float distance;
    float height;
    float height_per_half_diagonal;
};
using GroundHeight = std::function<float(float x, float z)>;

// The generated world's rings: a walker at the chunk's edge, low flight, a high overview.
std::vector<eval::CameraPose> chunk_camera_poses(const WorldTerrain& terrain, const ChunkSquare& square);

// Rings for an imported capture at scale σ (world_import.h): the ground rings above with heights
// times σ, or for an aerial capture views from above and oblique only.
std::vector<eval::CameraPose> capture_chunk_camera_poses(const GroundHeight& ground, const ChunkSquare& square,
                                                         float scale, bool aerial);

// How many of `points` lie inside the pose's image (aspect × its vertical field of view), beyond `znear`.
std::size_t points_seen(const eval::CameraPose& pose, const std::vector<glm::vec3>& points, float aspect, float znear);

// A capture's training cameras (training_cameras.h, in the world frame) that see a chunk well: with a
// sample of up to 64 of its centres `fine`, those that have a quarter of the sample or more inside
// their image (in front of `znear`), standing within 8 chunk diagonals of the sample's middle. At most
// `most`, spread evenly over them sorted by distance (the nearest and the farthest kept); each focused on
// the sample's middle. Empty when none does.
std::vector<eval::CameraPose> chunk_training_poses(const std::vector<eval::CameraPose>& cameras,
                                                   const std::vector<glm::vec3>& fine, const ChunkSquare& square,
                                                   float aspect, float znear, std::size_t most = 16);

}  // namespace splat_lod::world
