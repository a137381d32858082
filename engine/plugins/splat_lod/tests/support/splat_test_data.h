#pragma once
// Splat test data without GL: the real captures (data_file("splats/...")), cameras that look at them and
// small clouds built in code. The GPU harness that renders them is in splat_test_scenes.h.
#include <filesystem>
#include <string>
#include <vector>

#include "engine/render/camera.h"
#include "splat_lod/core/splat_cloud.h"

namespace engine::test {

struct RealSplatScene {
    std::string name;
    std::filesystem::path path;
    glm::vec3 up;  // the capture's up direction (Y-down captures: (0, −1, 0))
};
std::vector<RealSplatScene> real_splat_scenes();

// Orbit cameras around the cloud's robust centre (median) at `distance_factor` × its robust radius
// (90th percentile distance), `count` views at different azimuths and elevations.
std::vector<CameraView> orbit_cameras(const splat_lod::SplatCloud& cloud, const glm::vec3& up, int count, int width,
                                      int height, float distance_factor = 2.2f);

// A cloud built in code: Gaussians with the given parameters (degree-0 SH from a linear colour).
struct GaussianSpec {
    glm::vec3 position{0.0f};
    glm::vec3 log_scale{-2.0f};
    glm::vec4 rotation{1, 0, 0, 0};  // w, x, y, z
    float opacity_logit = 2.0f;
    glm::vec3 color{0.5f};  // the colour SH degree 0 should give (before clamping)
};
splat_lod::SplatCloud make_cloud(const std::vector<GaussianSpec>& specs);

// `n` Gaussians swirled through the unit ball, sizes, rotations and opacities varying, colours
// 0.5 ± `colour_amplitude` in red and green, `blue` in blue: a scene for GPU-against-reference
// comparisons.
std::vector<GaussianSpec> swirl_specs(int n, float colour_amplitude, float blue);

// n³ small Gaussians on a lattice filling the unit cube around the origin, colours varying: a bake of
// it adds coarse levels in well under a second (the drop-in LOD and cache tests).
splat_lod::SplatCloud lattice_cloud(int n = 12);

}  // namespace engine::test
