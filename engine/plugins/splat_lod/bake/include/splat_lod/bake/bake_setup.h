#pragma once
// What a bake needs besides the scene: its cameras, the capture shape they stand for, and the settings
// that shape decides (capture_defaults). splat_bake builds a BakeSetup from its command line; the
// runtime's drop-in LOD ("lod": "auto" of a splat component) uses the defaults, which are those of
// `splat_bake --capture auto --cameras auto`.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/bake/bake.h"
#include "splat_lod/bake/bake_cameras.h"
#include "splat_lod/bake/capture_shape.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::bake {

// Which of the settings that a capture shape decides the user gave (those keep their given value).
struct GivenSettings {
    bool cells = false, enlargement = false, pooling = false, margin = false, axis_ratio = false, member = false,
         refine_cameras = false;
};

struct BakeSetup {
    std::string cameras = "auto";  // a bake_camera_poses() spec, "auto" or a camera file
    std::string capture = "auto";  // "auto", "orbit", "forward" or "world"
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    glm::vec3 forward{0.0f};  // generated grid cameras' view direction; zero: default_forward(up)
    int width = 512;          // bake camera image size
    int height = 384;
    BakeOptions options;  // the capture shape fills in every setting `given` does not mark
    GivenSettings given;
};

// The bake cameras and the capture shape they stand for, with the reason (one line): told by
// `capture`, implied by a generated spec, or detected from the cameras of a file; for "auto" cameras
// without a told shape, orbit.
struct CameraChoice {
    std::vector<eval::CameraPose> poses;
    CaptureShape shape = CaptureShape::orbit;
    std::string spec, reason;
};
CameraChoice choose_cameras(const std::string& cameras, const std::string& capture, const CameraPlacement& placement);

// The capture shape's settings (capture_defaults) for every one that `given` does not mark.
void apply_capture_defaults(BakeOptions& options, CaptureShape shape, const GivenSettings& given);

// A bake ready to run: the cameras at the setup's image size and the options with the capture shape's
// settings applied (not yet validated).
struct PreparedBake {
    std::vector<reference::ReferenceCamera> cameras;
    CameraChoice choice;
    BakeOptions options;
};
PreparedBake prepare_bake(const SplatCloud& fine, const BakeSetup& setup);

}  // namespace splat_lod::bake
