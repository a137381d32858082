#pragma once
// Private to the room scene: flat panels tiled with Gaussians, boxes made of panels, and the paints
// (colour as a function of the world position) of its surfaces.
#include "splat_lod/synth/synth_common.h"

#include <functional>

namespace splat_lod::synth::room {

// The colour at a point of a surface with the given outward unit normal. Paints draw from the rng
// at most once per call.
using Paint = std::function<glm::vec3(const glm::vec3& position, const glm::vec3& normal, Rng& rng)>;

// A rectangle: a corner and its two full edge vectors (orthogonal); the face looks along u × v.
struct Panel {
    glm::vec3 corner{0.0f};
    glm::vec3 u{1.0f, 0.0f, 0.0f};
    glm::vec3 v{0.0f, 1.0f, 0.0f};
};

// Tiles the panel with flat Gaussians on a jittered grid `spacing` / √detail apart (at least one
// per side), each 0.6 × its tile across and a tenth of that thick, opaque (logit 4–5).
void tile_panel(SplatCloud& cloud, const Panel& panel, float spacing, float detail, const Paint& paint, Rng& rng);

// The faces of the box [lo, hi] that can be seen when it stands on the floor: its top and four
// sides (no bottom), each tiled by tile_panel.
void tile_box(SplatCloud& cloud, const glm::vec3& lo, const glm::vec3& hi, float spacing, float detail,
              const Paint& paint, Rng& rng);

// A deterministic value in [0, 1) for integer coordinates (a lattice point of value noise).
float hash01(int a, int b, int c, std::uint64_t seed);

// Paints. `seed` varies colours between scenes; every paint multiplies in the fixed sun shading.
Paint floor_planks(std::uint64_t seed);
Paint rug_pattern(float x0, float z0, float x1, float z1);
Paint striped_wallpaper();
Paint panelled_wall(std::uint64_t seed);
Paint plain(const glm::vec3& rgb, float variation, float ambient);
Paint checker(const glm::vec3& a, const glm::vec3& b, float square);
Paint fabric_stripes(const glm::vec3& a, const glm::vec3& b, float period);
Paint drawers(float y0, float drawer_height);
Paint fine_stripes(float period);
Paint rings(const glm::vec3& centre, float period);

}  // namespace splat_lod::synth::room
