#pragma once
// What an evaluation writes into its output folder:
//   measurements.csv   every measurement (one row per scene, sweep, view, method, scale/distance),
//                      with the Gaussians drawn per level (drawn_l1..drawn_l4)
//   report.md          Yan et al.'s Table 1 shape (methods × scales: PSNR, SSIM, time) and the
//                      Gaussians drawn per level, the LOD verdict and the matched-count comparison
//                      (lod_report.h) where measured, the distance profile, the upscalers against
//                      native with their verdict (upscale_report.h), and links to the plots and
//                      pictures
//   *.png              gnuplot plots (time vs error, time vs distance, Gaussians vs distance)
//   contact_sheet.png  rows reference and methods, columns scales (first view)
//   upscale_crops.png  the upscale sweep's side-by-side crops (upscale_report.h)
//   levels.png         the first view with `full`, each Gaussian tinted by its level (when measured)
#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "splat_lod/eval/eval_run.h"

namespace splat_lod::eval {

// Means over the views of one method at one scale or distance.
struct Summary {
    int views = 0;
    std::optional<double> psnr, ssim;  // absent when any view lacks them
    double wall_ms = 0.0, splat_gpu_ms = 0.0;
    double upscale_gpu_ms = 0.0;  // the "splat.upscale" span (inside "splat"); 0 where absent
    double considered = 0.0, visible = 0.0, tile_splat_pairs = 0.0, resident_bytes = 0.0;
    std::array<double, 4> per_level{};  // Gaussians drawn per LOD level 1..4
};
Summary summarize(const EvalResults& results, Sweep sweep, const std::string& method, int factor);

void write_csv(const EvalResults& results, const std::filesystem::path& path);
// `renderer` is the GL renderer string, quoted in the setup line.
void write_markdown_report(const EvalResults& results, const std::string& renderer, const std::filesystem::path& path);
// Returns the plot files written, or nothing (with a warning logged) when gnuplot is missing.
std::vector<std::filesystem::path> write_plots(const EvalResults& results, const std::filesystem::path& folder);
// The contact sheet's rows: the reference, then options.sheet_methods (or every method of
// options.methods).
std::vector<std::string> contact_sheet_rows(const EvalOptions& options);
void write_contact_sheet(const EvalResults& results, const std::filesystem::path& path);
// One row of results.level_tiles and a legend of the level colours.
void write_level_picture(const EvalResults& results, const std::filesystem::path& path);

// All of the above into `folder` (created if needed).
void write_outputs(const EvalResults& results, const std::string& renderer, const std::filesystem::path& folder);

// "38.21", "∞" for +inf, "–" when absent.
std::string format_db(const std::optional<double>& value);
// "+4.21 dB", "-0.50 dB".
std::string format_signed_db(double value);
// `value` with `digits` decimals.
std::string format_fixed(double value, int digits);
// A Gaussian count for a table: "950", "120.3k", "1.25M" (means over views may be fractional).
std::string format_count(double value);
// Counts of levels 1..4 joined by slashes: "120.3k/2.1k/0/0".
std::string format_levels(const std::array<double, 4>& per_level);

}  // namespace splat_lod::eval
