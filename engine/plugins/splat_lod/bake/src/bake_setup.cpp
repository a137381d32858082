#include "splat_lod/bake/bake_setup.h"

#include <optional>

namespace splat_lod::bake {

CameraChoice choose_cameras(const std::string& cameras, const std::string& capture, const CameraPlacement& placement) {
    const std::optional<CaptureShape> told = parse_capture_shape(capture, "--capture");
    CameraChoice choice;
    choice.spec = cameras;
    if (cameras == "auto") {
        choice.shape = told.value_or(CaptureShape::orbit);
        choice.spec = auto_camera_spec(choice.shape);
        choice.reason = told ? "given by --capture"
                             : "no cameras to detect it from (the Gaussians alone do not show where the capture "
                               "stood), so the default; --capture forward or world chooses another";
    } else if (const auto implied = generated_capture_shape(cameras)) {
        choice.shape = told.value_or(*implied);
        choice.reason = told ? "given by --capture" : "implied by --cameras " + cameras;
    }
    choice.poses = bake_camera_poses(choice.spec, placement);
    if (cameras != "auto" && !generated_capture_shape(cameras)) {
        const CaptureDetection detection = detect_capture_shape(choice.poses, placement.extent);
        choice.shape = told.value_or(detection.shape);
        choice.reason = told ? "given by --capture; the cameras look like " + detection.reason
                             : "detected from the cameras: " + detection.reason;
    }
    return choice;
}

void apply_capture_defaults(BakeOptions& options, CaptureShape shape, const GivenSettings& given) {
    const BakeOptions d = capture_defaults(options, shape);
    if (!given.cells && !given.enlargement) {
        options.cells = d.cells;
        options.choose_recipe = d.choose_recipe;
    }
    if (!given.pooling) options.pooling = d.pooling;
    if (!given.margin) options.view_margin = d.view_margin;
    if (!given.axis_ratio) options.min_axis_ratio = d.min_axis_ratio;
    if (!given.member) options.member_ranges = d.member_ranges;
    if (!given.refine_cameras) options.refine_cameras = d.refine_cameras;
}

PreparedBake prepare_bake(const SplatCloud& fine, const BakeSetup& setup) {
    CameraPlacement placement;
    placement.extent = eval::robust_extent(fine.positions);
    placement.up = setup.up;
    placement.positions = fine.positions;
    placement.forward = setup.forward;
    PreparedBake prepared;
    prepared.choice = choose_cameras(setup.cameras, setup.capture, placement);
    prepared.cameras = bake_cameras(prepared.choice.poses, setup.width, setup.height);
    prepared.options = setup.options;
    apply_capture_defaults(prepared.options, prepared.choice.shape, setup.given);
    return prepared;
}

}  // namespace splat_lod::bake
