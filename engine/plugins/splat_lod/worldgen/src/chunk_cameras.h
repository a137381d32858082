#pragma once
// Internal to the world generator: the bake cameras of a chunk. A chunk is seen by a player walking
// or flying through the world, from inside it out to the far distance, so its coverage ranges and
// the refinement should come from such views (docs/algorithms.md §4: coverage ranges measured from
// the directions users view from are the ones that hold), not from an object orbit: three rings of views aimed at the
// chunk's middle, at eye height just outside it, low flight a few chunks away, and high above far away.
#include <vector>

#include "chunk_content.h"
#include "splat_lod/core/camera_set.h"
#include "splat_lod/worldgen/world_terrain.h"

namespace splat_lod::world {

inline constexpr int kChunkCameraRings = 3;
inline constexpr int kChunkCamerasPerRing = 8;
inline constexpr float kChunkCameraFovDeg = 60.0f;

std::vector<eval::CameraPose> chunk_camera_poses(const WorldTerrain& terrain, const ChunkSquare& square);

}  // namespace splat_lod::world
