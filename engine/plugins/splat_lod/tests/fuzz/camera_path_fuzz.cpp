// Camera-path files ([{"eye", "target", "up", "fov_y_deg", "name"}, ...]) through
// parse_camera_path, the text form of read_camera_path.
// Contract (splat_lod/core/camera_set.h): poses as checked in camera_checks.h, or engine::Error
// naming the file, the camera index and the problem.
#include "camera_checks.h"
#include "engine/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string name = "fuzz/path.json";
    std::vector<splat_lod::eval::CameraPose> poses;
    try {
        poses = splat_lod::eval::parse_camera_path(splat_fuzz::text_of(data, size), name);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, name);
        return 0;
    }
    splat_fuzz::check_poses(poses);
    return 0;
}
