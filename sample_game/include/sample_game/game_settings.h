#pragma once
// What the game runs with, in one place: the LOD settings the splat pass draws with AND the ones
// the chunk streamer decides residency with come from the same GameSettings::lod, so they cannot
// disagree (the streamer loads a finer level only from where the renderer could select it;
// splat_lod/stream/stream_policy.h). The budgets and the lens are here too.
#include <cstdint>
#include <filesystem>
#include <string>

#include "splat_lod/msgs/lod_settings.h"

#include "engine/render/fog_pass.h"

#include "splat_lod/stream/chunk_streamer.h"

namespace sample_game {

inline constexpr std::uint64_t kMiB = 1024ull * 1024ull;

struct GameSettings {
    plugin_msgs::LodSettings lod;  // mode, S_T, S_rel_min/max, render scale, upscaler, level colouring
    // GPU bytes of streamed Gaussians resident at the end of any frame, and uploaded in any frame.
    // Chosen on the default world along the walkthrough at 640x360 (sample_game/README.md,
    // "Budgets"), before chunk groups: stream level 4 of every chunk alone took ~280 MiB. With the
    // groups the path needs at most ~250 MiB and the overview 31 MiB, so 384 MiB leaves room; 8 MiB per
    // frame lets a chunk's fine level arrive within a frame or two.
    std::uint64_t memory_budget_bytes = 384 * kMiB;
    std::uint64_t upload_budget_bytes = 8 * kMiB;
    // GPU bytes the splat pass's buffers that follow the view may take in a frame (the projected splats and
    // the sort keys; SplatPassSettings::frame_memory_limit): a view that needs more is drawn in strips.
    // 0: no limit. See sample_game/README.md, "Budgets".
    std::uint64_t frame_memory_bytes = 16 * kMiB;
    int sh_degree = 0;  // SH degree the GPU stores (the generated world carries degree 0)
    // How the GPU stores the Gaussians (docs/gpu_storage.md): compact, 20 bytes each at degree 0, or
    // full floats, 76. The budgets above are bytes either way, so compact holds 3.8 times the Gaussians.
    splat_lod::GpuStorage gpu_storage = splat_lod::GpuStorage::compact;
    // Loads levels this much earlier than the on-axis bound (chunk_streamer.h: off axis a Gaussian
    // covers up to ~1/cos²θ more pixels, 1.5–2.4 at the edges and corners of this lens).
    float load_distance_scale = 1.5f;
    // Chunk groups replace their chunks where their pooling cell projects to at most this many pixels
    // (StreamerSettings::group_cell_px; 0: never, every chunk drawn from its own levels).
    float group_cell_px = 2.0f;
    // ... and below this elevation (degrees) by the projected area of the group's box, smaller at
    // grazing angles (StreamerSettings::group_grazing_deg); 0: by the cell's edge alone.
    float group_grazing_deg = 30.0f;
    // A chunk whose file could not be read (missing, cut short, replaced by a patcher or a running
    // regeneration) is tried again after this many frames, so that it comes back once its file does.
    int retry_failed_after_frames = 120;
    // Updates over which a chunk or group that starts or stops being drawn, or a level that arrives on
    // screen, fades in or out (StreamerSettings::fade_frames; 0: at once, as before fades existed).
    int fade_frames = 4;
    // Updates ahead that the streamer's cut anticipates the moving camera by
    // (StreamerSettings::anticipation_updates; 0: not at all).
    int anticipation_updates = 4;
    bool sync_streaming = false;  // reads inside update() instead of on the background thread
    float fov_y_deg = 60.0f;
    // The walkthrough's poses or keys from this file (path_file.h) instead of the world's own path.
    std::filesystem::path path_file;
    // Distance fog over meshes and splats by the frame's view depth (engine/render/fog_pass.h): on in
    // the windowed game (sample_game --no-fog turns it off), off in the harness unless asked for (--fog),
    // so that the walkthrough's numbers are the splats' own. GameWorld gives it the sky's colour.
    engine::FogSettings fog{.enabled = false, .density = 0.0015f};
};

// Throws engine::Error naming the first bad setting ("sample_game: lod_settings.rel_min: ...").
void validate(const GameSettings& settings);

// The streamer's settings: budgets, SH degree, load distances and the LOD thresholds of `lod`.
splat_lod::world::StreamerSettings streamer_settings(const GameSettings& settings);

// The near plane for an eye this high above the ground: 0.1 m on foot, growing with the height so
// that the far overview keeps depth precision between the terrain mesh and the props on it.
float near_plane_for(float height_above_ground_m);
// The far plane: beyond the farthest corner of the world from any point of the walkthrough.
float far_plane_for(float world_size_m);

}  // namespace sample_game
