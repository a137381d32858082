#pragma once
// The headless profile (`sample_game_harness --profile`): walks the camera path once with LOD and
// streaming, frame by frame, then (unless told not to) loads every chunk fully, switches to
// `baseline` mode and draws the overview's frames (and every K-th frame elsewhere) again, and
// writes what it measured:
//   <out>/profile.csv       one row per path frame of the LOD run (columns: frame_record.h)
//   <out>/baseline.csv      the baseline's frames, same columns
//   <out>/summary.txt       per-segment frame times and the three checks (profile_summary.h)
//   <out>/frame_time.png memory.png gaussians.png   (profile_plots.h; needs gnuplot)
//   <out>/frames/*.png      every K-th frame (LOD and baseline), and frames_sheet.png of them
//   <out>/frames_strip.png  kStripFrames consecutive LOD frames around the largest temporal_error, the
//                           reference above and the change from frame to frame below (frame_strip.h);
//                           without a reference, the overview's first frames
// When the world has a reference for the run's key (reference_cache.h), its frames are compared
// with it (a broken cached reference is an error naming its file), and so is the change between
// consecutive reference frames (temporal_error).
// The first view is streamed completely before the walk starts (preload, like a loading screen;
// its updates are drawn at a quarter of the size and not recorded), unless `preload` is off.
// Needs a current GL context. Budget checks that fail are results, not errors.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "sample_game/game_settings.h"
#include "sample_game/harness/profile_summary.h"

namespace sample_game {

struct ProfileOptions {
    std::filesystem::path world;  // folder holding world.json
    std::filesystem::path out = "out/game";
    int width = 640, height = 360;
    int frames = 400;  // poses along the path
    GameSettings settings;
    int frames_png_every = 0;  // 0: no frame pictures
    bool baseline = true;
    int baseline_every = 10;          // baseline frames outside the overview (0: overview only)
    int baseline_overview_every = 1;  // every K-th overview frame in the baseline (1: all of them)
    // Before the first frame, stream the first view completely (as a game's loading screen would),
    // so that the walk starts with what it needs rather than measuring a cold start.
    bool preload = true;
    // The supersampling factor of the reference to look for (reference_cache.h): when one is cached
    // for this world, size, frame count and field of view, its frames are drawn in the baseline too
    // and both CSVs get psnr_vs_reference, ssim_vs_reference and (LOD rows) seam_ratio.
    int reference_supersample = 3;
    // Whose reference: empty for `world`'s own; another world's folder to score this one against it
    // (the same world stored another way: its path must be the same, which the reference's key checks).
    std::filesystem::path reference_world;
    // > 0: each LOD frame is drawn again as a stereo pair this far apart (docs/stereo.md), its time and
    // its eyes' PSNR recorded (stereo_frame_ms, stereo_eye_psnr) and summarised per segment.
    float stereo_ipd = 0.0f;
    // Each LOD frame after the first is drawn again with the frame before's selection, and the switch
    // pop of the pair recorded (FrameRecord::switch_pop) and summarised.
    bool switch_pops = false;
};

struct ProfileOutcome {
    ProfileSummary summary;
    std::string summary_text;  // also in <out>/summary.txt
    std::vector<std::filesystem::path> pictures;
    std::string plot_problem;  // why there are no plots, if there are none
};

// Throws engine::Error naming the option ("sample_game_harness: --frames must be at least 10") or file.
void validate(const ProfileOptions& options);
// The checks every run along the path shares (the profile's and the reference's): a world folder,
// an image of 16..16384 px per side and at least 10 path frames.
void validate_path_run(const std::filesystem::path& world, int width, int height, int frames);

// Progress lines ("lod frame 120/400 (flyout), 0.31 s/frame, ETA 1m22s") go to `progress` (may be null).
ProfileOutcome run_profile(const ProfileOptions& options, std::FILE* progress);

}  // namespace sample_game
