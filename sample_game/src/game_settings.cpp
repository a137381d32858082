#include "sample_game/game_settings.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace sample_game {

void validate(const GameSettings& s) {
    if (const std::string error = s.lod.validate(); !error.empty()) engine::fail("sample_game: " + error);
    if (!(s.fov_y_deg > 1.0f && s.fov_y_deg < 170.0f))
        engine::fail("sample_game: the vertical field of view must be in (1, 170) degrees, got " +
                     std::to_string(s.fov_y_deg));
    if (const std::string error = engine::check_fog(s.fog); !error.empty()) engine::fail("sample_game: " + error);
    // The streamer checks budgets, SH degree and distances and names the setting.
    splat_lod::world::validate(streamer_settings(s));
}

splat_lod::world::StreamerSettings streamer_settings(const GameSettings& s) {
    splat_lod::world::StreamerSettings out;
    out.upload_budget_bytes_per_frame = s.upload_budget_bytes;
    out.memory_budget_bytes = s.memory_budget_bytes;
    out.gpu_sh_degree = s.sh_degree;
    out.gpu_pages = splat_lod::page_layout(s.gpu_storage);
    out.rule = s.lod.rule;  // a streamer with the game's bus follows the published settings anyway
    out.load_distance_scale = s.load_distance_scale;
    out.group_cell_px = s.group_cell_px;
    out.group_grazing_deg = s.group_grazing_deg;
    out.retry_failed_after_frames = s.retry_failed_after_frames;
    out.fade_frames = s.fade_frames;
    out.anticipation_updates = s.anticipation_updates;
    out.background_thread = !s.sync_streaming;
    return out;
}

float near_plane_for(float height_above_ground_m) {
    return std::clamp(0.02f * height_above_ground_m, 0.1f, 5.0f);
}

float far_plane_for(float world_size_m) {
    return 4.0f * world_size_m + 100.0f;
}

}  // namespace sample_game
