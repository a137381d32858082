#pragma once
// Internal to the world generator: where the structures stand. Houses along the path (each with a
// picket-fenced front garden made of Gaussians), runs of mesh fence segments beside the path and
// waymark posts, all as manifest props on the terrain, plus the keep-out areas that trees, rocks and
// grass avoid so that no prop stands inside a tree. Computed once per world from the seed, before
// any chunk, and shared read-only by the chunk workers.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/core/world_manifest.h"
#include "splat_lod/synth/world_terrain.h"

namespace splat_lod::world {

// Mesh files of the props, relative to the world's folder (written by world_meshes.cpp).
inline constexpr const char* kHouseMesh = "meshes/house.glb";
inline constexpr const char* kFenceMesh = "meshes/fence.glb";
inline constexpr const char* kPostMesh = "meshes/post.glb";
inline constexpr const char* kTerrainMesh = "meshes/terrain.glb";

// A capsule on the ground plane: the segment a → b (x, z) grown by radius.
struct KeepOut {
    glm::vec2 a{0.0f}, b{0.0f};
    float radius = 0.0f;
};

// A picket fence of Gaussians (synth::append_picket_fence) on the terrain.
struct PicketFenceSpec {
    glm::vec3 start{0.0f}, end{0.0f};
    float height = 0.9f;
    std::int64_t index = 0;  // its random stream
};

struct WorldLayout {
    std::vector<Prop> props;
    std::vector<PicketFenceSpec> picket_fences;
    std::vector<KeepOut> keep_out;

    // True when (x, z) is within `margin` of a keep-out capsule.
    bool blocked(const glm::vec2& p, float margin) const;
};

WorldLayout make_world_layout(const WorldTerrain& terrain, std::uint64_t seed);

// Yaw in whole degrees of a horizontal direction (x, z), measured as a rotation about +Y that takes
// +z to it: rounding to whole degrees keeps the bytes of the props independent of the platform's
// atan2 rounding.
float yaw_degrees(const glm::vec2& direction);

}  // namespace splat_lod::world
