#pragma once
// The cameras a bake measures coverage in and refines against. A user with the training output
// passes its INRIA cameras.json (or a camera path); without one, a generated set stands in for the
// views the scene will be seen from, matched to the capture shape (capture_shape.h): rings of views
// around an object, a grid of eyes on the capture side of a forward-facing scene, eyes inside a world
// looking out. The generated sets are deliberately different from the evaluation's orbit, so
// evaluations see held-out views.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/bake/capture_shape.h"
#include "splat_lod/core/camera_set.h"
#include "splat_lod/core/reference_renderer.h"

namespace splat_lod::bake {

// Where generated cameras stand.
struct CameraPlacement {
    eval::SceneExtent extent;              // the robust centre and radius (rings, inside, and grid without positions)
    glm::vec3 up{0.0f, 1.0f, 0.0f};        // the scene's up direction
    glm::vec3 forward{0.0f};               // grid: the view direction of the capture; zero: default_forward(up)
    std::span<const glm::vec3> positions;  // grid: the Gaussians' means (empty: the extent's sphere stands in)
};

// The view direction of a camera whose image right is +X and whose image up is `up`: up × +X, i.e. −Z
// for Y-up scenes (the engine's and OpenGL's camera convention) and +Z for Y-down captures (OpenCV's).
// Fails when `up` is zero or parallel to X.
glm::vec3 default_forward(const glm::vec3& up);

// Specs:
//   "rings:RxA"   R elevations (−0.15, 0.2, 0.55 rad for 3; spread over −0.2…0.7 otherwise) × A azimuths
//                 offset from ring to ring, at 2.2× the robust radius, 50° field of view (R 1..64, A 1..256);
//   "grid:CxR" or "grid:CxRxD"  forward-facing: in the frame of the view direction f (right, up, f), C × R
//                 eyes spanning the middle half of the Gaussians' 5th–95th percentile width and height, on
//                 the plane of their 2nd percentile along f (the capture side), repeated on D planes
//                 0, 12, 24 … % of the depth (2nd–98th percentile) further in (default D = 2); each looks
//                 along f turned by up to ±20° of yaw (left columns left) and ±10° of pitch (low rows down),
//                 50° field of view (C, R 1..64, D 1..8);
//   "inside:RxA"  world: R rings of A eyes at 0.6·(r + ½)/R of the robust radius from the centre (and 5 % of
//                 it above), each looking outward along its azimuth, pitched 0.1 rad down (R 1..16, A 1..64);
//   "auto"        rings:3x8 (the capture shape's own default is auto_camera_spec());
// anything else is an evaluation camera spec (orbit:N, INRIA cameras.json, a camera path). Errors name the
// spec or file and the problem.
std::vector<eval::CameraPose> bake_camera_poses(const std::string& spec, const CameraPlacement& placement);
std::vector<eval::CameraPose> bake_camera_poses(const std::string& spec, const eval::SceneExtent& extent,
                                                const glm::vec3& up);

// The generated set that stands for "auto" per capture shape: rings:3x8, grid:8x6x3, inside:2x8.
std::string auto_camera_spec(CaptureShape shape);
// The capture shape a generated spec stands for (rings, orbit → orbit; grid → forward; inside → world);
// nullopt for "auto" and camera files.
std::optional<CaptureShape> generated_capture_shape(const std::string& spec);

// The reference (double-precision) cameras of the poses at width × height.
std::vector<reference::ReferenceCamera> bake_cameras(const std::vector<eval::CameraPose>& poses, int width, int height);

}  // namespace splat_lod::bake
