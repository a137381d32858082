// What the temporal sweep writes (splat_lod/eval/temporal_sweep.h): temporal.csv, temporal.md, a
// gnuplot plot of the pair errors along each path and each path's strip of frames around its peak.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/core/gnuplot.h"
#include "engine/core/log.h"
#include "splat_lod/eval/eval_report.h"
#include "splat_lod/eval/sheet_drawing.h"
#include "splat_lod/eval/temporal_sweep.h"

namespace splat_lod::eval {
namespace {

constexpr int kStripLabelWidth = 96;
constexpr int kGap = 2;
constexpr int kMaxStripTileWidth = 480;

std::string number(double value, int digits) {
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    if (std::isnan(value)) return "NaN";
    return format_fixed(value, digits);
}

std::string optional_number(const std::optional<double>& value, int digits) {
    return value ? number(*value, digits) : std::string();
}

double max_pair_error(const TemporalRow& row, int& frame) {
    const auto it = std::max_element(row.pair_errors.begin(), row.pair_errors.end());
    frame = it == row.pair_errors.end() ? 0 : static_cast<int>(it - row.pair_errors.begin()) + 1;
    return it == row.pair_errors.end() ? 0.0 : *it;
}

std::string dat_name(const std::string& path, const std::string& method) {
    return "temporal_" + path + "_" + method + ".dat";
}

// Columns: frame t, the pair error of (t−1, t) (NaN at t = 0), PSNR of frame t, splat ms of frame t,
// the pop and the switch pop of (t−1, t) (NaN at t = 0).
void write_dat(const TemporalRow& row, const std::filesystem::path& file) {
    std::ostringstream out;
    out << "# frame pair_error_8bit psnr_db splat_gpu_ms pop_8bit switch_pop_8bit (" << row.method << " on " << row.path
        << ")\n";
    const bool timed = static_cast<int>(row.splat_ms.size()) == row.frames;
    for (int t = 0; t < row.frames; ++t) {
        const auto i = static_cast<std::size_t>(t);
        out << t << ' ' << (t == 0 ? std::string("NaN") : number(row.pair_errors[i - 1], 6)) << ' '
            << (std::isfinite(row.psnr[i]) ? number(row.psnr[i], 6) : std::string("NaN")) << ' '
            << (timed ? number(row.splat_ms[i], 6) : std::string("NaN")) << ' '
            << (t == 0 ? std::string("NaN") : number(row.pair_pops[i - 1], 6)) << ' '
            << (t == 0 ? std::string("NaN") : number(row.pair_switch_pops[i - 1], 6)) << '\n';
    }
    engine::write_text_file_atomic(file, out.str());
}

std::string plot_script(const TemporalResults& results, const std::string& path) {
    const TemporalOptions& o = results.options;
    std::string plots;
    int colour = 1;
    for (const Method& method : o.methods) {
        if (!plots.empty()) plots += ", \\\n     ";
        const std::string file = "'" + dat_name(path, method.name) + "'", lc = std::to_string(colour++);
        plots += file + " using 1:5 with linespoints pt 7 ps 0.6 lc " + lc + " title '" + method.name +
                 ": pop', \\\n     " + file + " using 1:6 with lines dt 2 lw 2 lc " + lc + " title '" + method.name +
                 ": switch pop'";
    }
    return "set output 'temporal_" + path + ".png'\nset title '" + o.scene_name + ": pops along the " + path +
           " path'\nset xlabel 'frame t (pair t-1, t)'\nset ylabel '99.9th percentile over pixels (8-bit "
           "units)'\nplot " +
           plots + "\n";
}

// Returns the plot files written, or nothing (with a warning) when gnuplot is missing.
std::vector<std::filesystem::path> write_temporal_plots(const TemporalResults& results,
                                                        const std::filesystem::path& folder) {
    std::string terminal = engine::gnuplot_png_terminal();
    if (terminal.empty()) {
        engine::log_warning("splat_eval: gnuplot with a PNG terminal was not found; no temporal plots written");
        return {};
    }
    std::string script = "set terminal " + terminal +
                         " size 720,480\nset termoption noenhanced\nset grid\nset key below\n"
                         "set datafile missing 'NaN'\nset yrange [0:*]\n";
    std::vector<std::filesystem::path> plots;
    for (const std::string& path : results.paths) {
        for (const TemporalRow& row : results.rows)
            if (row.path == path) write_dat(row, folder / dat_name(path, row.method));
        script += plot_script(results, path);
        plots.push_back(folder / ("temporal_" + path + ".png"));
    }
    engine::write_text_file_atomic(folder / "temporal.gp", script);
    engine::run_gnuplot(folder, "temporal.gp", "temporal.log");
    return plots;
}

std::string strip_caption(const TemporalStrip& strip) {
    std::ostringstream out;
    out << "*" << strip.path << ": frames " << strip.first_frame << "\u2013" << strip.first_frame + kStripFrames - 1
        << " around the largest switch pop (" << strip.peak_method << ", frames " << strip.peak_frame - 1 << "\u2192"
        << strip.peak_frame << ", " << number(strip.peak_pop, 2)
        << "); rows the reference and the methods, last row |M_t \u2212 M_t with the selection of t\u22121| \u00d7 "
        << kStripDifferenceGain << " of " << strip.peak_method
        << " for each pair (under its second frame): what switched.*\n\n";
    return out.str();
}

std::string markdown(const TemporalResults& results, const std::string& renderer) {
    const TemporalOptions& o = results.options;
    const int s = results.supersampling;
    std::ostringstream out;
    out << "## " << o.scene_name << ": temporal sweep\n\nOutput " << o.width << "\u00d7" << o.height
        << "; reference: the baseline render of the fine model at " << s * o.width << "\u00d7" << s * o.height
        << " (supersampling s = " << s << ") area-averaged by " << s << "\u00d7" << s
        << ". Temporal error: the mean over consecutive frame pairs of the mean |(M_t \u2212 M_{t\u22121}) \u2212 "
           "(R_t \u2212 R_{t\u22121})| over pixels and RGB channels, in 8-bit units (0\u2013255). Pop: the 99.9th "
           "percentile over pixels of the same difference averaged over RGB, per pair (a switch in one frame counts "
           "whole, a fade over k frames 1/k): its largest and mean over the path. Switch pop: the same percentile of "
           "|M_t \u2212 M_t with the selection of t\u22121| (the selection's change alone: motion and its aliasing "
           "cancel, baseline scores 0). Splat ms: the mean "
           "over the frames of the splat pass's GPU time, one timed frame each (GPU: "
        << renderer << "; compare methods within one run).\n\n"
        << "| path | frames | method | temporal error | largest pair (frame) | pop peak | pop mean | switch pop peak | "
           "switch pop mean | PSNR mean (dB) | splat ms mean |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const TemporalRow& row : results.rows) {
        int frame = 0;
        const double peak = max_pair_error(row, frame);
        out << "| " << row.path << " | " << row.frames << " | " << row.method << " | " << number(row.temporal_error, 3)
            << " | " << number(peak, 2) << " (" << frame << ") | " << number(row.pop_peak, 2) << " | "
            << number(row.pop_mean, 2) << " | " << number(row.switch_pop_peak, 2) << " | "
            << number(row.switch_pop_mean, 2) << " | " << number(row.psnr_mean, 2) << " | "
            << (row.splat_ms_mean ? number(*row.splat_ms_mean, 2) : "\u2013") << " |\n";
    }
    out << '\n';
    for (const TemporalStrip& strip : results.strips)
        out << "![pop along " << strip.path << "](temporal_" << strip.path << ".png)\n\n![strip of " << strip.path
            << "](temporal_strip_" << strip.path << ".png)\n\n"
            << strip_caption(strip);
    return out.str();
}

}  // namespace

void write_temporal_csv(const TemporalResults& results, const std::filesystem::path& path) {
    std::string text =
        "method,path,frames,temporal_error,psnr_mean,splat_ms_mean,pop_peak,pop_mean,switch_pop_peak,switch_pop_mean\n";
    for (const TemporalRow& row : results.rows)
        text += row.method + ',' + row.path + ',' + std::to_string(row.frames) + ',' + number(row.temporal_error, 4) +
                ',' + number(row.psnr_mean, 4) + ',' + optional_number(row.splat_ms_mean, 3) + ',' +
                number(row.pop_peak, 3) + ',' + number(row.pop_mean, 3) + ',' + number(row.switch_pop_peak, 3) + ',' +
                number(row.switch_pop_mean, 3) + '\n';
    engine::write_text_file_atomic(path, text);
}

engine::Image temporal_strip_image(const TemporalStrip& strip) {
    if (strip.images.empty() || strip.images.front().empty())
        engine::fail("splat_lod::eval::temporal_strip_image(): the strip of \"" + strip.path + "\" has no frames");
    const engine::Image& first = strip.images.front().front();
    const int tw = std::min(first.width, kMaxStripTileWidth);
    const int th = std::max(1, tw * first.height / first.width);
    const int rows = static_cast<int>(strip.images.size()) + (strip.differences.empty() ? 0 : 1);
    engine::Image sheet =
        black_image(kStripLabelWidth + kStripFrames * (tw + kGap), kLabelHeight + rows * (th + kGap) + kLabelHeight);
    for (int c = 0; c < kStripFrames; ++c) {
        const int frame = strip.first_frame + c;
        std::string label = "frame " + std::to_string(frame);
        if (frame == strip.peak_frame - 1 || frame == strip.peak_frame) label += " *";
        draw_text(sheet, kStripLabelWidth + c * (tw + kGap) + 4, 4, label);
    }
    const auto draw_row = [&](int r, const std::string& label, const std::vector<engine::Image>& images, int column0) {
        const int y0 = kLabelHeight + r * (th + kGap);
        draw_text(sheet, 4, y0 + th / 2 - 4, label);
        for (std::size_t i = 0; i < images.size(); ++i)
            draw_scaled(sheet, images[i], kStripLabelWidth + (column0 + static_cast<int>(i)) * (tw + kGap), y0, tw, th);
    };
    for (std::size_t r = 0; r < strip.images.size(); ++r) {
        const std::string& name = r < strip.rows.size() ? strip.rows[r] : std::string("?");
        draw_row(static_cast<int>(r), name == strip.peak_method ? name + " *" : name, strip.images[r], 0);
    }
    if (!strip.differences.empty())
        draw_row(static_cast<int>(strip.images.size()),
                 "switched x" + std::to_string(static_cast<int>(kStripDifferenceGain)), strip.differences, 1);
    draw_text(sheet, 4, sheet.height - kLabelHeight + 4,
              strip.path + ": peak " + strip.peak_method + " frames " + std::to_string(strip.peak_frame - 1) + "-" +
                  std::to_string(strip.peak_frame) + ", switch pop " + number(strip.peak_pop, 2) + " (8-bit)");
    return sheet;
}

void write_temporal_outputs(const TemporalResults& results, const std::string& renderer,
                            const std::filesystem::path& folder) {
    if (results.rows.empty()) engine::fail("splat_lod::eval::write_temporal_outputs(): no measurements");
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) engine::fail(folder.string() + ": cannot create the output folder: " + ec.message());
    write_temporal_csv(results, folder / "temporal.csv");
    engine::write_text_file_atomic(folder / "temporal.md", markdown(results, renderer));
    write_temporal_plots(results, folder);
    for (const TemporalStrip& strip : results.strips)
        engine::write_png(folder / ("temporal_strip_" + strip.path + ".png"), temporal_strip_image(strip));
}

}  // namespace splat_lod::eval
