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
    // A meandering centre line: across(along) = offset + Σ a·size·sin(2π·along / (λ·size) + φ)
    // over two terms (the river's x(z), the path's z(x)).
    struct CentreLine {
        const float* amplitude;   // a, 2 terms, in world sizes
        const float* wavelength;  // λ, 2 terms, in world sizes
        double phase[2];
        float offset;
        float across(float along, float size) const;
        float slope(float along, float size) const;  // d across / d along
        // Distance of (across, along) from the line: the offset projected on the line's normal,
        // exact for a straight line and close enough for bends far wider than river or path.
        float distance(float across_value, float along, float size) const;
    };

    float size_;
    std::uint64_t hill_seed_[3];
    std::uint64_t forest_seed_[2];
    CentreLine river_, path_;
};

}  // namespace splat_lod::world
