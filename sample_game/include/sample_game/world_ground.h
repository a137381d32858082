#pragma once
// What a walkthrough needs of a world's ground: its height, where the walk runs, how large the world
// is and at what scale. A generated world answers from its terrain (splat_lod/synth/world_terrain.h,
// rebuilt from the manifest's seed); a world imported from a capture (splat_lod/worldgen/world_import.h)
// from the ground grid its manifest holds (the 10th percentile of the heights per chunk), walking
// straight along x through the densest chunk, at its scale σ = chunk size / 64 (a capture's unit is
// unknown, so its lengths follow its chunks).
#include <optional>

#include <glm/glm.hpp>

#include "splat_lod/core/world_manifest.h"
#include "splat_lod/synth/world_terrain.h"

namespace sample_game {

class WorldGround {
public:
    // A generated world's terrain (implicit: the terrain alone is a complete ground).
    WorldGround(const splat_lod::world::WorldTerrain& terrain);  // NOLINT(google-explicit-constructor)
    // The manifest's ground grid when it has one (an imported world), else its terrain from the seed.
    static WorldGround of(const splat_lod::world::WorldManifest& manifest);

    float height(float x, float z) const;
    float size() const { return size_; }
    float scale() const { return scale_; }
    bool imported() const { return !terrain_; }
    // The walk's centre line z(x), its unit direction at x, and the x where the walk starts.
    float path_z(float x) const;
    glm::vec2 path_direction(float x) const;
    float walk_start() const { return walk_start_; }
    // The point the overview looks at: the world's centre on the ground.
    glm::vec3 centre() const { return {0.0f, height(0.0f, 0.0f), 0.0f}; }

private:
    WorldGround() = default;

    std::optional<splat_lod::world::WorldTerrain> terrain_;
    splat_lod::world::GroundGrid grid_;
    float size_ = 0.0f, scale_ = 1.0f, walk_start_ = 0.0f, walk_z_ = 0.0f;
};

// The walk's length along the ground and the canopy segment's first rise, for a world of this size.
struct WalkLengths {
    float walk;
    float canopy;
};
WalkLengths walk_lengths(const WorldGround& ground);

}  // namespace sample_game
