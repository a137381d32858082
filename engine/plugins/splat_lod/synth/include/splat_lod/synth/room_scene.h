#pragma once
// A forward-facing indoor test scene: one side of a room as a hand-held capture sees it, with the
// camera grid of that capture and held-out views beside it. It is the test case of bakes for
// forward-facing captures (docs/lod.md, "Forward-facing captures"): the cameras stand in a small box
// near the open end of the room and look across it, so content lies from about 2 m (two crates in
// front of the capture) to 9 m (the far wall) away.
//
// Conventions and reproducibility as in fine_detail_scene.h: Y up, metres, SH degree 0, level 1, the
// same seed gives the same bytes on every platform.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "splat_lod/core/camera_set.h"
#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::synth {

// The room: x in ±kRoomHalfWidth, floor y = 0, ceiling y = kRoomHeight, far wall z = kRoomFarZ; floor,
// side walls and ceiling run to z = kRoomOpenZ, and the room is open towards +z (behind the capture,
// where a forward-facing capture sees nothing).
constexpr float kRoomHalfWidth = 3.0f;
constexpr float kRoomHeight = 3.0f;
constexpr float kRoomFarZ = -8.0f;
constexpr float kRoomOpenZ = 2.0f;

struct RoomOptions {
    std::uint64_t seed = 1;
    float detail = 1.0f;  // [kMinDetail, kMaxDetail]; the Gaussian count is close to proportional
};

// Planked floor with a patterned rug, striped wallpaper on the far wall, panelled side walls, a
// plain ceiling, a bookshelf of many narrow book spines, a table with a tiled top, a striped sofa,
// a cabinet with drawers, two chequered crates near the capture and two finely striped pictures.
// The layout is fixed; the seed changes colours, book sizes and small offsets. Surfaces are tiled
// with flat Gaussians 1.5–10 cm apart, so that their texture is finer than a pixel from a few metres
// at 256×192 and aliases when the room is seen small. At detail 1 it holds 164,144 Gaussians (seed 1).
constexpr std::size_t kRoomGaussiansMin = 100'000;
constexpr std::size_t kRoomGaussiansMax = 200'000;

SplatCloud make_room_scene(const RoomOptions& options = {});

// The capture: `columns` × `rows` eyes (1–64 each) in the box x in ±1 m, y in 1.3…1.7 m, z in
// 0.4…0.8 m (rows alternate in depth), each looking across the room towards the far wall with a
// small turn that follows its place in the grid (±8° yaw, a few degrees of pitch); 50° field of view.
// Errors name the argument.
std::vector<eval::CameraPose> room_capture_cameras(int columns = 6, int rows = 4);

// Eight views in the capture's neighbourhood and none on its grid: between the grid's eyes, a step
// into the room and a step back, turned up to 20° further than the capture turns.
std::vector<eval::CameraPose> room_held_out_cameras();

// The poses as a camera-path JSON (docs/tools.md, "Camera sets"): eye, target (the eye plus the
// focus distance along the view), up, fov_y_deg and name per camera.
std::string camera_path_json(const std::vector<eval::CameraPose>& poses);

}  // namespace splat_lod::synth
