#pragma once
// The shape of the capture a scene was trained from, which decides where generated bake cameras
// stand (docs/lod.md, "Forward-facing captures"):
//   - orbit:   cameras around an object, looking at it (rings of views around the scene);
//   - forward: a forward-facing sweep, cameras on one side of the scene looking across it, all within
//              a cone of view directions (a grid of eyes on the capture side);
//   - world:   a large world with the cameras inside the content, looking out in many directions.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/bake/bake.h"
#include "splat_lod/core/camera_set.h"

namespace splat_lod::bake {

enum class CaptureShape { orbit, forward, world };

const char* capture_shape_name(CaptureShape shape);

// "auto" → nullopt; "orbit", "forward", "world" → the shape. Anything else throws engine::Error
// naming `option` and the text.
std::optional<CaptureShape> parse_capture_shape(const std::string& text, const std::string& option = "--capture");

// What detect_capture_shape() measured, and what it concluded.
struct CaptureDetection {
    CaptureShape shape = CaptureShape::orbit;
    glm::vec3 mean_direction{0.0f, 0.0f, -1.0f};  // unit mean of the view directions (−z when they cancel)
    float cone_deg = 180.0f;            // the 95th percentile (all of them below 20 cameras) of the angles to it
    float one_side_fraction = 0.0f;     // cameras behind the scene centre along the mean direction
    float towards_centre_deg = 180.0f;  // median angle between a view direction and the way to the centre
    float inside_fraction = 0.0f;       // cameras within the scene's robust radius of its centre
    std::string reason;                 // one line: the shape and the numbers that decided it
};

// Thresholds of the rules below.
inline constexpr float kForwardConeDeg = 60.0f;
inline constexpr float kForwardOneSide = 0.9f;
inline constexpr float kOrbitTowardsCentreDeg = 35.0f;
inline constexpr float kWorldInside = 0.5f;

// The capture shape of a camera set around a scene of the given extent, by these rules in order:
//   1. forward: the view directions lie within kForwardConeDeg of their mean and at least
//      kForwardOneSide of the cameras stand behind the scene centre along that mean (one side);
//   2. orbit: the cameras look at the centre (median angle below kOrbitTowardsCentreDeg);
//   3. world: at least kWorldInside of the cameras stand inside the robust radius, looking out;
//   4. otherwise orbit, saying that no rule matched.
// A pure function of its input. An empty set is orbit ("no cameras").
CaptureDetection detect_capture_shape(const std::vector<eval::CameraPose>& cameras, const eval::SceneExtent& extent);

// The bake settings measured for the capture shape (docs/lod.md, "Forward-facing captures"), on top
// of `options`. Forward: moment-matched pooling on the adaptive cells (no recipe choice), coarse
// Gaussians no thinner than 0.3 of their largest axis, coverage_max capped where the members stop
// being drawn, and every bake camera in the refinement. Orbit and world: unchanged.
BakeOptions capture_defaults(BakeOptions options, CaptureShape shape);

// Above kWorldCaptureGaussians Gaussians, or for a flat capture of at least kFlatCaptureGaussians whose
// centres (1st–99th percentile box) are kFlatCaptureRatio times wider than the box is thin (an aerial
// capture: a single file's bake cameras orbit it from far away, so its coarse levels serve only the
// overview), one LOD file serves a capture badly; a streamed world (splat_world --from) is what it needs.
// (Reported for a 4.2M aerial capture: a single-file bake added 0.13 % coarse Gaussians and still drew 3.2M
// of 4.25M from four times the overview's distance; docs/results.md, "Captures of your own".) The
// thresholds themselves are judgement, not measured optima. Returns why, or "" when one file is fine.
inline constexpr std::uint64_t kWorldCaptureGaussians = 2'000'000;
inline constexpr std::uint64_t kFlatCaptureGaussians = 1'000'000;
inline constexpr double kFlatCaptureRatio = 15.0;
std::string streamed_world_advice(const SplatCloud& cloud);

}  // namespace splat_lod::bake
