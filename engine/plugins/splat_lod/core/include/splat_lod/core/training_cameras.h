#pragma once
// A capture's training cameras, the views it was made from: INRIA `cameras.json` (the 3DGS training
// output, camera_set.h) or COLMAP's text model, `images.txt` with `cameras.txt` beside it:
//   images.txt: two lines per image, "IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME" (the world-to-camera
//               rotation as a unit quaternion and translation, OpenCV axes: x right, y down, z forward)
//               and a line of 2D points (ignored, possibly empty; a file without them loses no image);
//               lines starting with '#' are comments;
//   cameras.txt: "CAMERA_ID MODEL WIDTH HEIGHT PARAMS..." (the field of view comes from HEIGHT and the
//               focal length: PARAMS[1] for the models with fx and fy, PARAMS[0] for those with one f).
// The camera's centre is −Rᵀt; it looks along Rᵀ's third column. Errors name the file, the line and the
// problem.
#include <filesystem>
#include <string>
#include <vector>

#include "splat_lod/core/camera_set.h"

namespace splat_lod::eval {

// `images` and `cameras` are the two files' text; the names are those errors give.
std::vector<CameraPose> parse_colmap_cameras(const std::string& images, const std::string& cameras,
                                             const std::string& images_name, const std::string& cameras_name);

// The files read_training_cameras() reads for `path`: the cameras.json (or camera path) itself, or an
// images.txt and the cameras.txt beside it, found in a folder as below. Throws engine::Error naming a
// folder that holds neither; files are not checked for existence here.
std::vector<std::filesystem::path> training_camera_files(const std::filesystem::path& path);

// A cameras.json, an images.txt (its cameras.txt beside it), or a folder holding either (a COLMAP
// `sparse/0`, a 3DGS output folder). Throws engine::Error naming the path when it holds none.
std::vector<CameraPose> read_training_cameras(const std::filesystem::path& path);

}  // namespace splat_lod::eval
