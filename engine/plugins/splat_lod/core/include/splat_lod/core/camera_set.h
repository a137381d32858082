#pragma once
// The cameras an evaluation renders, independent of the output size (which each sweep sets):
//   - INRIA `cameras.json` (the 3DGS training output): [{id, img_name, width, height, position[3],
//     rotation[3][3] (camera-to-world, OpenCV axes: x right, y down, z forward), fx, fy}, ...];
//   - a camera-path file: [{"eye": [x,y,z], "target": [x,y,z], "up": [x,y,z], "fov_y_deg": 50}, ...]
//     ("up" defaults to [0,1,0], "fov_y_deg" to 50, an optional "name");
//   - a generated orbit ("orbit:N") around the scene's robust centre.
// Errors name the file, the camera index and the problem.
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/render/camera.h"

namespace splat_lod::eval {

struct CameraPose {
    std::string name;
    glm::vec3 eye{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit
    glm::vec3 up{0.0f, 1.0f, 0.0f};        // unit, orthogonal to forward
    float fov_y = 0.87f;                   // radians
    // Distance along the view ray to the point the camera looks at; the distance sweep dollies
    // out from that point.
    float focus_distance = 1.0f;

    glm::vec3 target() const { return eye + forward * focus_distance; }
};

// A camera `factor` times farther from its target along the same view ray.
CameraPose dolly(const CameraPose& pose, float factor);
// The engine camera for a pose at a given output size (near/far from the focus distance).
engine::CameraView make_view(const CameraPose& pose, int width, int height);

std::vector<CameraPose> read_inria_cameras(const std::filesystem::path& path);
std::vector<CameraPose> read_camera_path(const std::filesystem::path& path);
// The same from text already in memory; `name` is the file named in error messages.
std::vector<CameraPose> parse_inria_cameras(const std::string& text, const std::string& name);
std::vector<CameraPose> parse_camera_path(const std::string& text, const std::string& name);

// Where the scene is: the median of the Gaussian centres and the 90th-percentile distance from it.
struct SceneExtent {
    glm::vec3 centre{0.0f};
    float radius = 1.0f;
};
SceneExtent robust_extent(const std::vector<glm::vec3>& points);

// `count` views at distance_factor × radius around the centre, alternating elevations (the same
// orbit as the gpu tests' orbit_cameras).
std::vector<CameraPose> orbit_poses(const SceneExtent& extent, const glm::vec3& up, int count,
                                    float distance_factor = 2.2f);

// "orbit:N" or a file (INRIA cameras.json when its entries have "rotation", else a path file).
// Path-file and INRIA cameras get focus distances from the scene centre projected on their ray.
std::vector<CameraPose> load_camera_set(const std::string& spec, const SceneExtent& extent, const glm::vec3& up);

}  // namespace splat_lod::eval
