#pragma once
// The walkthrough of a world, derived from its ground (world_ground.h: a generated world's terrain, an
// imported world's ground grid) so that it fits any world without loading a chunk:
//   ground    eye height (1.7 m) along the path, where it runs through the most forest within a
//             quarter of the world from the centre, looking ahead along it;
//   canopy    rising over the path to the tree tops (the trees are 4.5–9 m tall, so 11 m flies
//             just over their crowns) and on along it, looking ahead and down into them;
//   flyout    pulling back and up, behind the walk, to the overview;
//   overview  a quarter orbit around the world's centre, high and far (0.42·size up, 0.6·size
//             out: the whole world in view), looking at the centre;
//   return    down in an arc to the start of the walk, landing on the path where the path began,
//             so a looping walkthrough has no jump.
// Distances along the ground scale with the world (a 96 m test world gets a 9 m walk), heights
// above the ground do not (eye height, tree tops).
#include <optional>

#include "sample_game/camera_path.h"
#include "sample_game/world_ground.h"

namespace sample_game {

struct WorldPathShape {
    float eye_height_m = 1.7f;
    float canopy_height_m = 11.0f;
    float overview_radius = 0.6f;   // × world size, horizontal distance from the centre
    float overview_height = 0.42f;  // × world size, above the ground at the centre
    float overview_arc_deg = 90.0f;
    float min_clearance_m = 1.0f;  // poses are never lower than this above the ground
};

// The key poses of the walkthrough over this terrain.
std::vector<PathKey> make_world_path_keys(const WorldGround& ground, const WorldPathShape& shape = {});

// sample() of the world's path: on the walk the eye stays at eye height above the ground, and
// everywhere else at least shape.min_clearance_m above it (no shape: path_shape_for(ground)) (the spline between keys
// could otherwise dip into a hill between them).
std::vector<PathPose> sample_world_path(const WorldGround& ground, int frames,
                                        const std::optional<WorldPathShape>& shape = std::nullopt,
                                        const std::array<float, kSegmentCount>& shares = kDefaultSegmentShares);

// The point the overview looks at: the world's centre on the ground.
glm::vec3 world_centre(const WorldGround& ground);

// The default shape for this ground: as above for a generated world; for an imported one, heights at
// its scale and at least 0.5 % (eye) and 3 % (canopy) of the world's size.
WorldPathShape path_shape_for(const WorldGround& ground);

}  // namespace sample_game
