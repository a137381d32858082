#pragma once
// What splat_lod/core/camera_set.h promises of every pose a camera file gives: a finite eye,
// unit `forward`, unit `up` orthogonal to it, a field of view in (0, 180°) and a positive finite
// focus distance.
#include <cmath>
#include <vector>

#include "splat_fuzz_support.h"
#include "splat_lod/core/camera_set.h"

namespace splat_fuzz {

inline void check_poses(const std::vector<splat_lod::eval::CameraPose>& poses) {
    require(!poses.empty(), "a camera file gives at least one camera");
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const auto& pose = poses[i];
        const std::string camera = "camera " + std::to_string(i) + ": ";
        require(finite(pose.eye), camera + "finite eye");
        require(finite(pose.forward) && unit_length(pose.forward), camera + "unit forward");
        require(finite(pose.up) && unit_length(pose.up), camera + "unit up");
        require(std::fabs(glm::dot(pose.forward, pose.up)) < 1e-3f, camera + "up orthogonal to forward");
        require(pose.fov_y > 0.0f && pose.fov_y < 3.14159265f, camera + "field of view in (0, 180 degrees)");
        require(std::isfinite(pose.focus_distance) && pose.focus_distance > 0.0f, camera + "positive focus distance");
    }
}

}  // namespace splat_fuzz
