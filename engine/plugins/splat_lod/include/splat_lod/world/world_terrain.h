#pragma once
// The generated world's ground, as functions of the horizontal position (x, z) in metres, Y up: a
// seeded height field of gentle hills, a river winding across the world from −z to +z in a valley
// carved into them, a path winding across from −x to +x, and where forests grow. The chunk content,
// the props and the terrain mesh all read it; a game can use it to keep a walking camera on the
// ground (height()) without loading any chunk.
//
// Deterministic: the same seed and size give the same values on every IEEE 754 platform (the
// synth library's noise, sine and cosine; no fused multiply-adds: compiled with -ffp-contract=off).
#include <cstdint>

#include <glm/glm.hpp>

namespace splat_lod::world {

class WorldTerrain {
public:
    static constexpr float kRiverHalfWidth = 5.0f;  // water surface, metres either side of the centre line
    static constexpr float kPathHalfWidth = 1.3f;

    WorldTerrain(std::uint64_t seed, float size_m);

    float size() const { return size_; }
    // The ground (the top of the ground Gaussians; the river bed under the water).
    float height(float x, float z) const;
    // Unit normal of the ground from central differences of height().
    glm::vec3 normal(float x, float z) const;

    // The river's centre line x(z), its horizontal distance from (x, z), and its water surface
    // height at z (falling gently along the river).
    float river_x(float z) const;
    float river_distance(float x, float z) const;
    float water_level(float z) const;
    // The path's centre line z(x) and its horizontal distance from (x, z).
    float path_z(float x) const;
    float path_distance(float x, float z) const;
    // Unit direction of the path at x (along +x).
    glm::vec2 path_direction(float x) const;

    // How densely trees grow, in [0, 1]: 0 in meadows, near 1 deep in a forest.
    float forest(float x, float z) const;

private:
    float hills(float x, float z) const;
    float river_slope(float z) const;  // dx/dz of the centre line
    float path_slope(float x) const;   // dz/dx of the centre line

    float size_;
    std::uint64_t hill_seed_[3];
    std::uint64_t forest_seed_[2];
    double river_phase_[2];
    double path_phase_[2];
    float river_offset_, path_offset_;
};

}  // namespace splat_lod::world
