#pragma once
// The generated world's ground, as functions of the horizontal position (x, z) in metres, Y up: a
// seeded height field of gentle hills, a river winding across the world from −z to +z in a valley
// carved into them, a path winding across from −x to +x, and where forests grow. The chunk content,
// the props and the terrain mesh all read it; a game can use it to keep a walking camera on the
// ground (height()) without loading any chunk.
//
// Deterministic: the same seed, size and feature scale give the same values on every IEEE 754
// platform (the synth library's noise, sine and cosine; no fused multiply-adds: compiled with
// -ffp-contract=off).
//
// The feature scale: the river's and the path's bends are laid out in proportion to it, and so are
// their offsets from the centre. Hills and forests have their own wavelengths in metres. A world up to
// kFeatureScaleMax wide has the feature scale of its size, so its river and path cross it in one or two
// wide bends; a larger world keeps kFeatureScaleMax and continues them, so that its middle
// kFeatureScaleMax × kFeatureScaleMax is the world of that size with the same seed, with more land
// around it (world_layout.cpp places the props the same way).
#include <cstdint>

#include <glm/glm.hpp>

namespace splat_lod::world {

class WorldTerrain {
public:
    static constexpr float kRiverHalfWidth = 5.0f;  // water surface, metres either side of the centre line
    static constexpr float kPathHalfWidth = 1.3f;

    static constexpr float kFeatureScaleMax = 1024.0f;
    // The feature scale a world of `size_m` is generated with: min(size_m, kFeatureScaleMax).
    static float feature_scale_for(float size_m);

    // `feature_m` must be positive and at most size_m (world_manifest.h: `feature_m`).
    WorldTerrain(std::uint64_t seed, float size_m, float feature_m);

    float size() const { return size_; }
    float feature_scale() const { return feature_; }
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
    // A meandering centre line: across(along) = offset + Σ a·F·sin(2π·along / (λ·F) + φ) over two
    // terms (the river's x(z), the path's z(x)); F is the feature scale.
    struct CentreLine {
        const float* amplitude;   // a, 2 terms, in feature scales
        const float* wavelength;  // λ, 2 terms, in feature scales
        double phase[2];
        float offset;
        float across(float along, float scale) const;
        float slope(float along, float scale) const;  // d across / d along
        // Distance of (across, along) from the line: the offset projected on the line's normal,
        // exact for a straight line and close enough for bends far wider than river or path.
        float distance(float across_value, float along, float scale) const;
    };

    float size_, feature_;
    std::uint64_t hill_seed_[3];
    std::uint64_t forest_seed_[2];
    CentreLine river_, path_;
};

}  // namespace splat_lod::world
