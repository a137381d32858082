#pragma once
// The profile's verdict, computed from the measured frames (never asserted): per-segment frame
// times, peak memory and largest upload against the budgets, and the overview's LOD/baseline
// ratio, with a pass/fail line for each of the three conditions of the walkthrough:
//   1. resident GPU memory stays within the memory budget on every frame of the LOD run (and the
//      GPU scene's pages equal the streamer's count);
//   2. no frame uploads more than the upload budget;
//   3. the overview segment is at least kRequiredOverviewSpeedup× cheaper per frame with LOD and
//      streaming than the same frames in `baseline` mode with every chunk resident;
// and, where a supersampled reference was cached for the run (reference_cache.h), three more on its
// frames (PSNR against the reference):
//   4. the LOD image is never more than kReferenceMaxLossDb worse than the baseline's;
//   5. on the overview's reference frames the LOD image is at least kReferenceOverviewGainDb better
//      than the baseline's and at least kReferenceOverviewMinDb;
//   6. seam_ratio (chunk_borders.h) is at most kMaxSeamRatio on every reference frame;
// with the mean temporal_error (frame_strip.h) of each run over its consecutive reference pairs (a
// measurement, no check);
// and, given the image size and the world's size (WorldScale), how the LOD scales with the world:
//   7. the overview's median frame time is at most the ground's;
//   8. no overview frame draws more than kMaxOverviewGaussiansPerPixel Gaussians per output pixel,
//      no frame of the path more than kMaxPathGaussiansPerPixel;
//   9. on every ground frame at least kMinGroundCulledShare of the resident Gaussians are culled by the
//      frustum or skipped as too small before projection;
//  10. at the overview at most kMaxOverviewResidentShare of the world's GPU bytes are resident;
//  11. with a splat budget, no frame draws more than it;
// and of the splat pass's own GPU memory:
//  12. its peak (the scene's buffers and the per-frame buffers) is at most kMaxPassMemoryRatio× the peak
//      resident scene (pages in use);
// and with --fog (the windowed game's distance fog):
//  13. the fog pass's median GPU time is at most kMaxFogShare of the median frame.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sample_game/harness/frame_record.h"

namespace sample_game {

inline constexpr double kRequiredOverviewSpeedup = 5.0;
inline constexpr double kReferenceMaxLossDb = 0.5;
inline constexpr double kReferenceOverviewGainDb = 3.0;
inline constexpr double kReferenceOverviewMinDb = 30.0;
inline constexpr double kMaxSeamRatio = 1.25;
inline constexpr double kMaxPassMemoryRatio = 1.5;
inline constexpr double kMaxOverviewGaussiansPerPixel = 1.5;
inline constexpr double kMaxPathGaussiansPerPixel = 2.5;
inline constexpr double kMinGroundCulledShare = 0.6;
inline constexpr double kMaxOverviewResidentShare = 0.15;
inline constexpr double kMaxFogShare = 0.03;

// What the scale checks (7–11) need beyond the rows; zeros leave those checks unmeasured.
struct WorldScale {
    std::uint64_t pixels = 0;        // output pixels per frame
    std::uint64_t world_bytes = 0;   // the whole world's GPU bytes with every level resident
    std::uint64_t splat_budget = 0;  // the run's splat budget (0: none)
};

struct SegmentTimes {
    int frames = 0;
    double mean_ms = 0.0, median_ms = 0.0, max_ms = 0.0;
    int baseline_frames = 0;          // frames of this segment also drawn in the baseline run
    double baseline_median_ms = 0.0;  // over those frames
    double lod_median_same_ms = 0.0;  // the LOD run's median over the same frames
};

struct Check {
    bool measured = false;  // false: not measured (e.g. --no-baseline); neither pass nor fail
    bool pass = false;
    std::string text;  // "PASS  memory: peak 97.3 MiB <= budget 128 MiB on all 400 frames"
};

// One reference frame: the LOD and baseline images against the reference (−1: not drawn/compared).
struct ReferenceFrameResult {
    int frame = 0;
    Segment segment = Segment::ground;
    double lod_psnr = -1.0, lod_ssim = -1.0, baseline_psnr = -1.0, baseline_ssim = -1.0, seam_ratio = -1.0;
    double baseline_seam_ratio = -1.0;  // the same measure of the baseline image, for comparison
    // seam_ratio_same_distance of the LOD and of the baseline image.
    double seam_ratio_same_distance = -1.0, baseline_seam_ratio_same_distance = -1.0;
    // temporal_error of the frame against its predecessor (−1: the predecessor has no reference).
    double lod_temporal_error = -1.0, baseline_temporal_error = -1.0;
};

// The mean temporal_error of a run's rows that have one, and the largest.
struct TemporalErrors {
    int pairs = 0;
    double mean = 0.0, largest = 0.0;
    int largest_frame = -1;
    double pop_mean = 0.0, pop_peak = 0.0;  // over the same pairs (FrameRecord::pop)
    int pop_peak_frame = -1;
};

struct ProfileSummary {
    int frames = 0;
    std::array<SegmentTimes, kSegmentCount> segments{};
    std::uint64_t memory_budget_bytes = 0, upload_budget_bytes = 0;
    std::uint64_t peak_resident_bytes = 0, peak_gpu_total_bytes = 0;
    std::uint64_t peak_scene_bytes = 0, peak_frame_bytes = 0;  // the two parts of the peak frame's total
    std::uint64_t max_upload_bytes = 0, max_gpu_upload_bytes = 0, total_upload_bytes = 0;
    int frames_over_memory = 0, frames_over_upload = 0, frames_pages_differ = 0;
    std::uint64_t failures = 0;
    // Overview, LOD against baseline over the frames both runs drew: ratio of the mean frame times
    // (= of their sums), and the smallest per-frame ratio.
    int overview_pairs = 0;
    double overview_lod_mean_ms = 0.0, overview_baseline_mean_ms = 0.0;
    std::optional<double> overview_speedup, overview_min_frame_speedup;
    // What LOD and streaming cost in image quality over those frames: mean PSNR (dB) and SSIM of the
    // LOD run's images against the baseline's (none when the images were not compared).
    std::optional<double> overview_psnr, overview_ssim;
    Check memory, upload, overview;
    std::vector<ReferenceFrameResult> reference_frames;  // empty: no reference
    TemporalErrors lod_temporal, baseline_temporal;      // pairs 0: not measured
    Check reference_loss, reference_overview, reference_seams;
    Check scale_time, scale_density, scale_culling, scale_memory, splat_budget;
    Check pass_memory;
    Check fog;
    int reselected_frames = 0;  // frames whose steps 1–2 ran again (FrameRecord::selection_runs)
    int striped_frames = 0;     // frames drawn in more than one strip (FrameRecord::strips)
    int most_strips = 1;
};

ProfileSummary summarize(const std::vector<FrameRecord>& lod, const std::vector<FrameRecord>& baseline,
                         std::uint64_t memory_budget_bytes, std::uint64_t upload_budget_bytes,
                         const WorldScale& scale = {});

// Context lines the summary prints around the numbers.
struct SummaryContext {
    std::string world;     // folder and size
    std::string settings;  // resolution, LOD mode and thresholds, budgets
    double wall_seconds = 0.0;
    std::string timing;                // where the wall time went
    std::vector<std::string> outputs;  // "profile.csv: one row per frame", ...
    std::string reference;             // whether a reference was found, and where
};

std::string format_summary(const ProfileSummary& summary, const SummaryContext& context);

// The temporal errors of `rows` (those ≥ 0).
TemporalErrors temporal_errors(const std::vector<FrameRecord>& rows);

// Median of a list (0 for none).
double median_of(std::vector<double> values);

}  // namespace sample_game
