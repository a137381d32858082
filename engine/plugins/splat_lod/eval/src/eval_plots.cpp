// Plots through gnuplot: the numbers go to .dat files (one per sweep and method) and the drawing
// commands to plots.gp, both kept in the output folder so a plot can be restyled and redrawn by
// hand with `gnuplot plots.gp`.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/core/gnuplot.h"
#include "engine/core/log.h"
#include "splat_lod/eval/eval_report.h"

namespace splat_lod::eval {
namespace {

// gnuplot skips "NaN" points, which is what a missing or infinite PSNR should be on a plot.
std::string dat_value(const std::optional<double>& value) {
    if (!value || !std::isfinite(*value)) return "NaN";
    return std::to_string(*value);
}

void write_dat(const EvalResults& results, Sweep sweep, const std::string& method, const std::vector<int>& factors,
               const std::filesystem::path& path) {
    std::ostringstream out;
    out << "# factor splat_gpu_ms wall_ms psnr_db ssim drawn tile_splat_pairs (means over views)\n";
    for (int f : factors) {
        const Summary s = summarize(results, sweep, method, f);
        out << f << ' ' << s.splat_gpu_ms << ' ' << s.wall_ms << ' ' << dat_value(s.psnr) << ' ' << dat_value(s.ssim)
            << ' ' << s.visible << ' ' << s.tile_splat_pairs << '\n';
    }
    engine::write_text_file_atomic(path, out.str());
}

std::vector<std::string> method_names(const EvalOptions& o) {
    std::vector<std::string> names;
    for (const auto& method : o.methods) names.push_back(method.name);
    return names;
}

std::string plot_list(const std::vector<std::string>& methods, const std::string& prefix,
                      const std::string& using_columns, const std::string& style, const std::string& suffix = "",
                      int first_colour = 1) {
    std::string list;
    int colour = first_colour;
    for (const auto& method : methods) {
        if (!list.empty()) list += ", \\\n     ";
        list += "'" + prefix + "_" + method + ".dat' using " + using_columns + " with " + style + " lc " +
                std::to_string(colour++) + " title '" + method + suffix + "'";
    }
    return list;
}

// The methods' curves carry scale labels; comparison scenes (e.g. a chain's levels) are thinner
// dotted curves without labels, so that many of them stay readable.
std::string scale_script(const EvalResults& results) {
    const auto& o = results.options;
    const std::vector<std::string> methods = method_names(o);
    std::string labels, comparisons;
    for (const auto& method : methods)
        labels += ", \\\n     'scale_" + method +
                  ".dat' using 2:4:(sprintf('%dx', $1)) with labels offset char 1,0.6 font ',8' notitle";
    std::vector<std::string> comparison_names;
    for (const auto& comparison : o.comparisons) comparison_names.push_back(comparison.method);
    if (!comparison_names.empty())
        comparisons = ", \\\n     " + plot_list(comparison_names, "scale", "2:4", "linespoints dt 3 pt 1", "",
                                                static_cast<int>(methods.size()) + 1);
    return "set output 'time_vs_error.png'\nset title '" + o.scene_name +
           ": splat pass time against error (labels: scale)'\nset xlabel 'GPU splat pass time (ms)'\n"
           "set ylabel 'PSNR (dB) vs reference'\nset logscale x\nunset logscale y\nplot " +
           plot_list(methods, "scale", "2:4", "linespoints pt 7") + comparisons + labels + "\n";
}

std::string distance_script(const EvalResults& results) {
    const std::string& scene = results.options.scene_name;
    const std::vector<std::string> methods = measured_methods(results.options, Sweep::distance);
    return "set output 'time_vs_distance.png'\nset title '" + scene +
           ": frame time as the camera moves away'\nset xlabel 'distance factor d (screen size 1/d)'\n"
           "set ylabel 'time (ms)'\nset logscale x 2\nset logscale y\nplot " +
           plot_list(methods, "distance", "1:3", "linespoints pt 7", " wall") + ", \\\n     " +
           plot_list(methods, "distance", "1:2", "linespoints dt 2 pt 6", " GPU splat pass") +
           "\nset output 'gaussians_vs_distance.png'\nset title '" + scene +
           ": Gaussians drawn (solid) and tile-splat pairs (dashed)'\nset ylabel 'count'\nplot " +
           plot_list(methods, "distance", "1:6", "linespoints pt 7", " drawn") + ", \\\n     " +
           plot_list(methods, "distance", "1:7", "linespoints dt 2 pt 6", " pairs") + "\n";
}

bool has(const EvalResults& results, Sweep sweep) {
    for (Sweep s : results.options.sweeps)
        if (s == sweep) return true;
    return false;
}

}  // namespace

std::vector<std::filesystem::path> write_plots(const EvalResults& results, const std::filesystem::path& folder) {
    std::string terminal = engine::gnuplot_png_terminal();
    if (terminal.empty()) {
        engine::log_warning("splat_eval: gnuplot with a PNG terminal was not found; no plots written");
        return {};
    }
    terminal += " size 720,480";
    std::string script = "set terminal " + terminal +
                         "\nset termoption noenhanced\nset grid\nset key below\nset datafile missing 'NaN'\n";
    std::vector<std::filesystem::path> plots;
    const auto& o = results.options;
    if (has(results, Sweep::scale)) {
        for (const auto& m : measured_methods(o, Sweep::scale))
            write_dat(results, Sweep::scale, m, o.scales, folder / ("scale_" + m + ".dat"));
        script += scale_script(results);
        plots.push_back(folder / "time_vs_error.png");
    }
    if (has(results, Sweep::distance)) {
        for (const auto& m : measured_methods(o, Sweep::distance))
            write_dat(results, Sweep::distance, m, o.distances, folder / ("distance_" + m + ".dat"));
        script += distance_script(results);
        plots.push_back(folder / "time_vs_distance.png");
        plots.push_back(folder / "gaussians_vs_distance.png");
    }
    engine::write_text_file_atomic(folder / "plots.gp", script);
    engine::run_gnuplot(folder);
    return plots;
}

}  // namespace splat_lod::eval
