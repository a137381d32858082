#include "sample_game/harness/profile_plots.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/core/gnuplot.h"
#include "sample_game/game_settings.h"

namespace sample_game {
namespace {

// Light fills for the segments, in kSegmentNames order.
constexpr const char* kSegmentFill[kSegmentCount] = {"#dff0d8", "#c8e6c9", "#dbe9f6", "#fdebd0", "#ece2f0"};

std::string mib(std::uint64_t bytes) {
    return std::to_string(static_cast<double>(bytes) / static_cast<double>(kMiB));
}

// Counts on a log axis: a zero is a missing point, not a fall to the bottom of the plot.
std::string count(std::uint64_t value) {
    return value == 0 ? std::string("NaN") : std::to_string(value);
}

void write_dat(const std::filesystem::path& folder, const std::vector<FrameRecord>& lod,
               const std::vector<FrameRecord>& baseline) {
    std::ostringstream l;
    l << "# frame frame_ms height_m resident_MiB upload_MiB gpu_upload_MiB drawn_l1 drawn_l2 drawn_l3 drawn_l4 "
         "visible\n";
    for (const auto& r : lod)
        l << r.frame << ' ' << r.frame_ms << ' ' << r.height_above_ground_m << ' ' << mib(r.resident_bytes) << ' '
          << mib(r.stream_upload_bytes) << ' ' << mib(r.gpu_upload_bytes) << ' ' << count(r.drawn_per_level[0]) << ' '
          << count(r.drawn_per_level[1]) << ' ' << count(r.drawn_per_level[2]) << ' ' << count(r.drawn_per_level[3])
          << ' ' << count(r.visible) << '\n';
    engine::write_text_file_atomic(folder / "lod.dat", l.str());
    std::ostringstream b;
    b << "# frame frame_ms visible (baseline: every chunk resident, mode baseline)\n";
    for (const auto& r : baseline) b << r.frame << ' ' << r.frame_ms << ' ' << count(r.visible) << '\n';
    engine::write_text_file_atomic(folder / "baseline.dat", b.str());
}

// Shaded, labelled frame ranges of the segments (the LOD run visits every frame in order).
std::string segment_objects(const std::vector<FrameRecord>& lod) {
    std::string out;
    int object = 1;
    for (std::size_t i = 0; i < lod.size();) {
        std::size_t j = i;
        while (j + 1 < lod.size() && lod[j + 1].segment == lod[i].segment) ++j;
        const auto k = static_cast<std::size_t>(lod[i].segment);
        const double x0 = lod[i].frame - 0.5, x1 = lod[j].frame + 0.5;
        out += "set object " + std::to_string(object++) + " rect from " + std::to_string(x0) + ", graph 0 to " +
               std::to_string(x1) + ", graph 1 behind fc rgb '" + kSegmentFill[k] + "' fs solid 1.0 noborder\n";
        out += "set label " + std::to_string(object) + " '" + std::string(kSegmentNames[k]) + "' at " +
               std::to_string(0.5 * (x0 + x1)) + ", graph 0.97 center front font ',9'\n";
        i = j + 1;
    }
    return out;
}

struct Ranges {
    // The y range tops, with room above the data for the segment labels: the larger of budget and
    // peak for memory and upload, the most Gaussians drawn (either run) on the log axis.
    double memory_top_mib, upload_top_mib, gaussians_top;
};

Ranges ranges_for(const std::vector<FrameRecord>& lod, const std::vector<FrameRecord>& baseline,
                  std::uint64_t memory_budget, std::uint64_t upload_budget) {
    std::uint64_t peak = memory_budget, upload = upload_budget, drawn = 10;
    for (const auto& r : lod) {
        peak = std::max({peak, r.resident_bytes, r.gpu_page_bytes});
        upload = std::max({upload, r.stream_upload_bytes, r.gpu_upload_bytes});
        drawn = std::max(drawn, r.visible);
    }
    for (const auto& r : baseline) drawn = std::max(drawn, r.visible);
    return {1.3 * static_cast<double>(peak) / kMiB, 1.3 * static_cast<double>(upload) / kMiB,
            8.0 * static_cast<double>(drawn)};
}

std::string script(const std::string& terminal, const std::vector<FrameRecord>& lod,
                   const std::vector<FrameRecord>& baseline, std::uint64_t memory_budget, std::uint64_t upload_budget) {
    const bool has_baseline = !baseline.empty();
    const std::string segments = segment_objects(lod);
    const Ranges range = ranges_for(lod, baseline, memory_budget, upload_budget);
    const std::string baseline_time = has_baseline ? ", \\\n     'baseline.dat' using 1:2 with linespoints pt 7 ps 0.6 "
                                                     "lc rgb '#c62828' title 'baseline, every chunk resident'"
                                                   : "";
    const std::string baseline_count = has_baseline ? ", \\\n     'baseline.dat' using 1:3 with points pt 7 ps 0.5 lc "
                                                      "rgb '#c62828' title 'baseline: all drawn (level 1)'"
                                                    : "";
    std::string s =
        "set termoption noenhanced\nset datafile missing 'NaN'\n"
        "set grid front\nset key below\nset xlabel 'frame along the path'\n" +
        segments;
    s += "set terminal " + terminal +
         " size 1000,520\nset output 'frame_time.png'\n"
         "set title 'Frame time along the walkthrough (render to glFinish)'\n"
         "set ylabel 'frame time (ms, log)'\nset logscale y\nset y2label 'camera height above ground (m)'\n"
         "set y2tics\nset ytics nomirror\nplot 'lod.dat' using 1:2 with lines lw 2 lc rgb '#1565c0' title 'LOD + "
         "streaming'" +
         baseline_time +
         ", \\\n     'lod.dat' using 1:3 axes x1y2 with lines dt 2 lc rgb '#616161' title 'camera height (right)'\n";
    s += "unset y2label\nunset y2tics\nset ytics mirror\nunset logscale y\n";
    s += "set terminal " + terminal +
         " size 1000,760\nset output 'memory.png'\n"
         "set multiplot layout 2,1 title 'GPU memory and uploads of the streamed world'\nset key below\n"
         "set title 'resident streamed Gaussians'\nset ylabel 'MiB'\nset yrange [0:" +
         std::to_string(range.memory_top_mib) +
         "]\n"
         "plot 'lod.dat' using 1:4 with lines lw 2 lc rgb '#1565c0' title 'resident', \\\n     " +
         mib(memory_budget) +
         " with lines dt 2 lw 2 lc rgb '#c62828' title 'memory budget'\n"
         "set title 'uploaded per frame'\nset yrange [0:" +
         std::to_string(range.upload_top_mib) +
         "]\n"
         "plot 'lod.dat' using 1:5 with impulses lw 2 lc rgb '#2e7d32' title 'streamed upload', \\\n"
         "     'lod.dat' using 1:6 with points pt 1 ps 0.5 lc rgb '#6a1b9a' title 'GPU scene upload (+ freed-page "
         "records)', \\\n     " +
         mib(upload_budget) +
         " with lines dt 2 lw 2 lc rgb '#c62828' title 'upload budget'\nunset multiplot\n"
         "set yrange [*:*]\n";
    s += "set terminal " + terminal +
         " size 1000,520\nset output 'gaussians.png'\n"
         "set title 'Gaussians drawn per LOD level along the walkthrough'\n"
         "set ylabel 'Gaussians drawn (log)'\nset logscale y\nset yrange [1:" +
         std::to_string(range.gaussians_top) +
         "]\n"
         "plot 'lod.dat' using 1:7 with lines lw 2 lc rgb '#757575' title 'level 1 (finest)', \\\n"
         "     'lod.dat' using 1:8 with lines lw 2 lc rgb '#2e7d32' title 'level 2', \\\n"
         "     'lod.dat' using 1:9 with lines lw 2 lc rgb '#1565c0' title 'level 3', \\\n"
         "     'lod.dat' using 1:10 with lines lw 2 lc rgb '#c62828' title 'level 4 (coarsest)', \\\n"
         "     'lod.dat' using 1:11 with lines dt 2 lc rgb '#000000' title 'all levels'" +
         baseline_count + "\n";
    return s;
}

}  // namespace

PlotResult write_profile_plots(const std::filesystem::path& folder, const std::vector<FrameRecord>& lod,
                               const std::vector<FrameRecord>& baseline, std::uint64_t memory_budget_bytes,
                               std::uint64_t upload_budget_bytes) {
    PlotResult result;
    if (lod.empty()) {
        result.problem = "no frames to plot";
        return result;
    }
    const std::string terminal = engine::gnuplot_png_terminal();
    if (terminal.empty()) {
        result.problem =
            "gnuplot with a PNG terminal was not found, so no plots were drawn (install the Debian package "
            "gnuplot-nox, e.g. with scripts/setup, then run `gnuplot plots.gp` in " +
            folder.string() + ")";
    }
    write_dat(folder, lod, baseline);
    engine::write_text_file_atomic(folder / "plots.gp", script(terminal.empty() ? "pngcairo" : terminal, lod, baseline,
                                                               memory_budget_bytes, upload_budget_bytes));
    if (terminal.empty()) return result;
    // gnuplot's warnings (a level never drawn has no points on a log axis) go to plots.log.
    engine::run_gnuplot(folder);
    for (const char* name : {"frame_time.png", "memory.png", "gaussians.png"}) result.pictures.push_back(folder / name);
    return result;
}

}  // namespace sample_game
