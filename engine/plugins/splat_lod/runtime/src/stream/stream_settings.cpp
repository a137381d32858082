// The chunk streamer's checks of its settings (chunk_streamer.h, validate) and of a frame's view.
#include <cmath>
#include <string>

#include "engine/core/error.h"
#include "splat_lod/stream/chunk_streamer.h"
#include "stream_state.h"

namespace splat_lod::world {
namespace {

[[noreturn]] void settings_error(const std::string& message) {
    engine::fail("splat_lod::world::ChunkStreamer: " + message);
}

}  // namespace

void validate(const StreamerSettings& s) {
    if (s.gpu_sh_degree < 0 || s.gpu_sh_degree > kMaxShDegree)
        settings_error("gpu_sh_degree must be 0..3, got " + std::to_string(s.gpu_sh_degree));
    if (s.gpu_pages.page_gaussians < 1) settings_error("gpu_pages.page_gaussians must be at least 1");
    const std::uint64_t one = gpu_bytes(1, s.gpu_sh_degree, s.gpu_pages);
    if (s.upload_budget_bytes_per_frame < one)
        settings_error("upload_budget_bytes_per_frame (" + std::to_string(s.upload_budget_bytes_per_frame) +
                       ") is below one GPU page (" + std::to_string(one) + " bytes at SH degree " +
                       std::to_string(s.gpu_sh_degree) + ")");
    if (s.memory_budget_bytes == 0) settings_error("memory_budget_bytes must be positive");
    if (s.max_requests_in_flight < 1) settings_error("max_requests_in_flight must be at least 1");
    if (const std::string problem = s.rule.validate("rule"); !problem.empty()) settings_error(problem);
    if (!(s.load_distance_scale > 0.0f) || !std::isfinite(s.load_distance_scale))
        settings_error("load_distance_scale must be positive and finite");
    if (!(s.unload_distance_factor >= 1.0f) || !std::isfinite(s.unload_distance_factor))
        settings_error("unload_distance_factor must be finite and at least 1");
    if (s.unload_delay_frames < 0) settings_error("unload_delay_frames must not be negative");
    if (s.retry_failed_after_frames < 0) settings_error("retry_failed_after_frames must not be negative");
    if (s.fade_frames < 0 || s.fade_frames > 1000) settings_error("fade_frames must be in [0, 1000]");
    if (s.anticipation_updates < 0 || s.anticipation_updates > 1000)
        settings_error("anticipation_updates must be in [0, 1000]");
    if (!(s.group_grazing_deg >= 0.0f && s.group_grazing_deg <= 90.0f))
        settings_error("group_grazing_deg must be between 0 (off) and 90 degrees");
    if (!(s.group_cell_px >= 0.0f) || !std::isfinite(s.group_cell_px))
        settings_error("group_cell_px must be 0 (no groups) or positive, and finite");
}

void check_view(const StreamView& view) {
    const auto finite = [](const glm::vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    const std::string where = "splat_lod::world::ChunkStreamer::update(): ";
    if (!finite(view.camera_position)) engine::fail(where + "the camera position is not finite");
    if (!finite(view.camera_velocity)) engine::fail(where + "the camera velocity is not finite");
    if (!(view.focal_length_px > 0.0f) || !std::isfinite(view.focal_length_px))
        engine::fail(where + "the focal length must be positive and finite, got " +
                     std::to_string(view.focal_length_px));
    if (!(view.cut_scale >= 1.0f) || !std::isfinite(view.cut_scale))
        engine::fail(where + "the cut scale must be finite and at least 1, got " + std::to_string(view.cut_scale));
}

}  // namespace splat_lod::world
