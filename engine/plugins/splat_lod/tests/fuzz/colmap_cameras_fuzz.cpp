// COLMAP's text model (images.txt with cameras.txt) through parse_colmap_cameras. The input is both
// files: cameras.txt up to the first line "---", images.txt after it (all of it as images.txt when
// there is no such line, with an empty cameras.txt).
// Contract (splat_lod/core/training_cameras.h): poses as checked in camera_checks.h, or engine::Error
// naming one of the two files.
#include "camera_checks.h"
#include "engine/core/error.h"
#include "splat_lod/core/training_cameras.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text = splat_fuzz::text_of(data, size);
    const std::size_t split = text.find("\n---\n");
    const std::string cameras = split == std::string::npos ? std::string() : text.substr(0, split + 1);
    const std::string images = split == std::string::npos ? text : text.substr(split + 5);
    const std::string images_name = "fuzz/images.txt", cameras_name = "fuzz/cameras.txt";
    std::vector<splat_lod::eval::CameraPose> poses;
    try {
        poses = splat_lod::eval::parse_colmap_cameras(images, cameras, images_name, cameras_name);
    } catch (const engine::Error& e) {
        const std::string message = e.what();
        if (message.rfind(cameras_name, 0) != 0) splat_fuzz::check_error_names(e, images_name);
        return 0;
    }
    splat_fuzz::check_poses(poses);
    return 0;
}
