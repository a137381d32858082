#pragma once
// The upscale parts of report.md and upscale_crops.png, from the upscale sweep's means over the views:
//   - the table: per factor and upscaler, PSNR and SSIM against the native render, the GPU time of
//     the splat raster (the splat pass without "splat.upscale") and of the upscale, the frame's wall
//     time, and the speed-up over native (wall and GPU);
//   - the verdict against the gradient-aware upscaling targets: spline ≥ 3 dB above bicubic at 2×,
//     3× and 4×; 3× spline ≥ 38 dB against native; 3× spline frames ≥ 2.5× faster than native (a
//     target stated for 1920×1080: the report says at which size it was measured);
//   - the side-by-side crops: the first view's window of most detail in the native image, from
//     native and each upscaler, magnified by nearest neighbour so that pixels are visible.
#include <optional>
#include <string>
#include <vector>

#include "engine/render/image.h"
#include "splat_lod/eval/criterion.h"
#include "splat_lod/eval/eval_run.h"

namespace splat_lod::eval {

struct UpscaleEntry {
    int factor = 1;                                   // 1 for native
    std::string upscaler;                             // "native", "spline", ...
    int source_width = 0, source_height = 0;          // the splat raster's size
    std::optional<double> psnr, ssim;                 // against the native render
    double render_ms = 0.0;                           // GPU: "splat" − "splat.upscale"
    double upscale_ms = 0.0;                          // GPU: "splat.upscale" (upscale and composite)
    double frame_ms = 0.0;                            // wall
    std::optional<double> speedup_wall, speedup_gpu;  // native / this; absent without times
    bool upscale_timed = false;                       // every view recorded a "splat.upscale" span
};

// Native first, then each factor × upscaler in the options' order; empty without the sweep's rows.
std::vector<UpscaleEntry> upscale_entries(const EvalResults& results);
std::string upscale_table_markdown(const std::vector<UpscaleEntry>& entries);

struct UpscaleVerdictRow {
    int factor = 2;
    std::optional<double> spline_psnr, bicubic_psnr;
    std::optional<double> gain_over_bicubic_db;       // spline − bicubic; absent unless both finite
    std::optional<double> gain_over_plain_db;         // spline − spline_plain; absent unless both finite
    std::optional<double> speedup_wall, speedup_gpu;  // of the spline over native
};

struct UpscaleVerdict {
    int width = 0, height = 0;            // the output size the speed-up was measured at
    std::vector<UpscaleVerdictRow> rows;  // one per factor
    std::vector<Criterion> criteria;
};

// The targets (docs/algorithms.md §5 and the upscaling issue).
constexpr double kMinSplineGainDb = 3.0;     // spline − bicubic at 2×, 3×, 4×
constexpr double kMinSplinePsnr3x = 38.0;    // 3× spline against native (real scenes)
constexpr double kMinSplineSpeedup3x = 2.5;  // 3× spline frame speed-up over native at 1920×1080

// Present when the upscale sweep measured `spline`.
std::optional<UpscaleVerdict> upscale_verdict(const EvalResults& results);
std::string upscale_verdict_markdown(const UpscaleVerdict& verdict);

// The "### Upscale sweep" section of report.md (empty without the sweep's rows).
std::string upscale_section(const EvalResults& results);

// A square window of an image (clipped to the image when it is smaller).
struct CropWindow {
    int x = 0, y = 0, width = 0, height = 0;
};
constexpr int kCropSide = 96;
constexpr int kCropMagnification = 3;
// The side × side window (clipped to the image) of highest gradient energy (the sum of squared
// luma differences to the right and below), searched on a 4-pixel grid; the first on ties.
CropWindow detail_window(const engine::Image& image, int side = kCropSide);
// The columns of the crops: native, then bilinear, bicubic, lanczos3, spline, spline_plain where
// measured.
std::vector<std::string> upscale_crop_columns(const EvalOptions& options);
// One row per crop factor, one column per upscale_crop_columns; nothing without upscale_tiles.
void write_upscale_crops(const EvalResults& results, const std::filesystem::path& path);

}  // namespace splat_lod::eval
