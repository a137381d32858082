#pragma once
// `sample_game_harness --reference`: makes the profile's reference (reference_cache.h) for a world: loads
// every chunk fully, switches to `baseline` mode (bake level 1 only) and draws each chosen path frame
// at `supersample`× the profile's size per side, with the props and terrain mesh as in the profile,
// in tiles of at most `max_render_side` a side (tile_view() of engine/render/camera.h: the same
// camera, an off-centre window of it), then averages each supersample × supersample block of the
// 8-bit display-space values in float and stores the result rounded to 8 bits (the quantisation
// costs at most 0.5/255 per channel, about 59 dB: far above what the profile compares). A key that
// is cached already is only checked (read back), not made again, unless `force`.
// Needs a current GL context.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "engine/render/camera.h"
#include "sample_game/game_settings.h"
#include "sample_game/harness/reference_cache.h"
#include "splat_lod/eval/image_metrics.h"

namespace sample_game {

struct ReferenceOptions {
    std::filesystem::path world;
    int width = 640, height = 360;
    int frames = 400;       // poses along the path (the profile's --frames)
    GameSettings settings;  // the field of view and SH degree count; the LOD mode is baseline
    int supersample = kDefaultReferenceSupersample;
    int max_render_side = kReferenceMaxRenderSide;
    bool force = false;  // make it again even when cached
};

struct ReferenceOutcome {
    std::filesystem::path folder;
    bool cached = false;  // found complete: nothing was drawn
    std::vector<std::size_t> frames;
    double seconds = 0.0, load_seconds = 0.0;
    std::string text;  // what was done, for the console
};

// Throws engine::Error naming the option ("sample_game_harness: --supersample must be 3..8").
void validate(const ReferenceOptions& options);

// Progress lines ("sample_game_harness: reference frame 3/24 (canopy) ..., ETA 4m10s") go to `progress`.
ReferenceOutcome make_reference(const ReferenceOptions& options, std::FILE* progress);

// Draws `camera` (any size) in tiles of at most max_side × max_side pixels and returns the whole
// image, display-space values in [0, 1]. Each tile is drawn until complete (render_complete); one
// whose (Gaussian, tile) pairs exceed the largest key buffer the sort allows is drawn in quarters.
splat_lod::eval::FloatImage render_tiled(engine::Engine& engine, const engine::Scene& scene,
                                         const engine::CameraView& camera, int max_side);

}  // namespace sample_game
