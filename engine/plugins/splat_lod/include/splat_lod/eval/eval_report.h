#pragma once
// What an evaluation writes into its output folder:
//   measurements.csv   every measurement (one row per scene, sweep, view, method, scale/distance)
//   report.md          the paper's Table 1 shape (methods × scales: PSNR, SSIM, time), the
//                      distance profile, and links to the plots and contact sheet
//   *.png              gnuplot plots (time vs error, time vs distance, Gaussians vs distance)
//   contact_sheet.png  rows reference and methods, columns scales (first view)
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
    double considered = 0.0, visible = 0.0, tile_splat_pairs = 0.0, resident_bytes = 0.0;
};
Summary summarize(const EvalResults& results, Sweep sweep, const std::string& method, int factor);

void write_csv(const EvalResults& results, const std::filesystem::path& path);
// `renderer` is the GL renderer string, quoted in the setup line.
void write_markdown_report(const EvalResults& results, const std::string& renderer, const std::filesystem::path& path);
// Returns the plot files written, or nothing (with a warning logged) when gnuplot is missing.
std::vector<std::filesystem::path> write_plots(const EvalResults& results, const std::filesystem::path& folder);
void write_contact_sheet(const EvalResults& results, const std::filesystem::path& path);

// All of the above into `folder` (created if needed).
void write_outputs(const EvalResults& results, const std::string& renderer, const std::filesystem::path& folder);

// "38.21", "∞" for +inf, "–" when absent.
std::string format_db(const std::optional<double>& value);

}  // namespace splat_lod::eval
