// The temporal sweep's rendering (splat_lod/eval/temporal_sweep.h): every path frame by frame, the
// reference first, then every method (each frame also with the previous frame's selection, for the
// switch pop); only the previous frame of each is kept, and the frames of each path's strip are
// rendered again once its peak is known (the renderer is deterministic).
#include "splat_lod/eval/temporal_sweep.h"

#include <algorithm>
#include <numeric>

#include "engine/core/error.h"
#include "splat_lod/eval/frame_measurer.h"

namespace splat_lod::eval {
namespace {

struct Progress {
    const TemporalOptions& options;
    int total = 0;
    int done = 0;

    void step(const std::string& path, const std::string& what) {
        ++done;
        if (!options.progress) return;
        std::string line = "[";  // (appended: GCC 12 warns falsely on "[" + std::string)
        line += std::to_string(done) + "/" + std::to_string(total) + "] " + options.scene_name + " " + path + " " +
                what + " (temporal)";
        options.progress(line);
    }
};

// The baseline render of the fine model at s·W × s·H, area-averaged by s×s.
FloatImage reference_frame(FrameMeasurer& measurer, const CameraPose& pose, const TemporalOptions& o, int s) {
    const FloatImage full = to_float(measurer.render(truth_method(), make_view(pose, s * o.width, s * o.height)));
    return s == 1 ? full : area_average(full, s);
}

double mean(const std::vector<double>& values) {
    return values.empty() ? 0.0
                          : std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

// Frame t of a method as drawn and, from the second frame on, drawn again with the selection of the
// frame before (the switch pop).
void measure_frame(FrameMeasurer& measurer, const Method& method, const TemporalPath& path, std::size_t t,
                   const TemporalOptions& o, TemporalRow& row, FloatImage& previous, const FloatImage& reference,
                   const FloatImage& reference_previous) {
    const engine::CameraView view = make_view(path.poses[t], o.width, o.height);
    const FrameMeasurement measured = measurer.measure(method, view, 1, 0);
    FloatImage image = to_float(measured.image);
    row.psnr.push_back(psnr(image, reference));
    if (const auto it = measured.gpu_ms.find("splat"); it != measured.gpu_ms.end()) row.splat_ms.push_back(it->second);
    if (t > 0) {
        row.pair_errors.push_back(temporal_pair_error(previous, image, reference_previous, reference));
        row.pair_pops.push_back(temporal_pair_pop(previous, image, reference_previous, reference));
        const engine::CameraView frozen = with_selection_of(view, make_view(path.poses[t - 1], o.width, o.height));
        row.pair_switch_pops.push_back(selection_switch_pop(to_float(measurer.render(method, frozen)), image));
    }
    previous = std::move(image);
}

double peak(const std::vector<double>& values) {
    return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

std::vector<TemporalRow> render_path(FrameMeasurer& measurer, const TemporalPath& path, int s, Progress& progress) {
    const TemporalOptions& o = progress.options;
    std::vector<TemporalRow> rows(o.methods.size());
    std::vector<FloatImage> previous(o.methods.size());
    FloatImage reference_previous;
    for (std::size_t t = 0; t < path.poses.size(); ++t) {
        progress.step(path.name, "frame " + std::to_string(t));
        FloatImage reference = reference_frame(measurer, path.poses[t], o, s);
        for (std::size_t m = 0; m < o.methods.size(); ++m)
            measure_frame(measurer, o.methods[m], path, t, o, rows[m], previous[m], reference, reference_previous);
        reference_previous = std::move(reference);
    }
    for (std::size_t m = 0; m < rows.size(); ++m) {
        TemporalRow& row = rows[m];
        row.method = o.methods[m].name;
        row.path = path.name;
        row.frames = static_cast<int>(path.poses.size());
        row.temporal_error = mean(row.pair_errors);
        row.pop_mean = mean(row.pair_pops);
        row.pop_peak = peak(row.pair_pops);
        row.switch_pop_mean = mean(row.pair_switch_pops);
        row.switch_pop_peak = peak(row.pair_switch_pops);
        row.psnr_mean = mean(row.psnr);
        if (!row.splat_ms.empty()) row.splat_ms_mean = mean(row.splat_ms);
    }
    return rows;
}

// The method and pair with the largest switch pop of a path (the first where several tie).
void find_peak(const std::vector<TemporalRow>& rows, TemporalStrip& strip) {
    strip.peak_pop = -1.0;
    for (const TemporalRow& row : rows)
        for (std::size_t i = 0; i < row.pair_switch_pops.size(); ++i)
            if (row.pair_switch_pops[i] > strip.peak_pop) {
                strip.peak_pop = row.pair_switch_pops[i];
                strip.peak_method = row.method;
                strip.peak_frame = static_cast<int>(i) + 1;
            }
}

TemporalStrip render_strip(FrameMeasurer& measurer, const TemporalPath& path, const std::vector<TemporalRow>& rows,
                           int s, Progress& progress) {
    const TemporalOptions& o = progress.options;
    TemporalStrip strip;
    strip.path = path.name;
    find_peak(rows, strip);
    const int frames = static_cast<int>(path.poses.size());
    strip.first_frame = std::clamp(strip.peak_frame - kStripFrames / 2, 0, frames - kStripFrames);
    strip.rows.push_back("reference");
    for (const Method& method : o.methods) strip.rows.push_back(method.name);
    strip.images.resize(strip.rows.size());
    for (int c = 0; c < kStripFrames; ++c) {
        const int t = strip.first_frame + c;
        progress.step(path.name, "strip frame " + std::to_string(t));
        const CameraPose& pose = path.poses[static_cast<std::size_t>(t)];
        strip.images[0].push_back(to_rgba8(reference_frame(measurer, pose, o, s)));
        for (std::size_t m = 0; m < o.methods.size(); ++m) {
            const engine::CameraView view = make_view(pose, o.width, o.height);
            strip.images[m + 1].push_back(measurer.render(o.methods[m], view));
            if (o.methods[m].name != strip.peak_method || c == 0) continue;
            const engine::CameraView frozen =
                with_selection_of(view, make_view(path.poses[static_cast<std::size_t>(t - 1)], o.width, o.height));
            const FloatImage image = to_float(strip.images[m + 1].back());
            strip.differences.push_back(temporal_difference_image(to_float(measurer.render(o.methods[m], frozen)),
                                                                  image, image, image, kStripDifferenceGain));
        }
    }
    return strip;
}

}  // namespace

TemporalResults run_temporal_sweep(FrameMeasurer& measurer, const std::vector<TemporalPath>& paths,
                                   const TemporalOptions& options) {
    validate_temporal_options(options);
    if (paths.empty()) engine::fail("splat_lod::eval::run_temporal_sweep(): no path given");
    for (std::size_t i = 0; i < paths.size(); ++i) {
        const TemporalPath& path = paths[i];
        if (static_cast<int>(path.poses.size()) < kMinTemporalFrames)
            engine::fail("temporal path \"" + path.name + "\": " + std::to_string(path.poses.size()) +
                         " frames are too few (at least " + std::to_string(kMinTemporalFrames) + ")");
        for (std::size_t j = 0; j < i; ++j)
            if (paths[j].name == path.name) engine::fail("temporal path \"" + path.name + "\": the name is used twice");
    }
    TemporalResults results;
    results.options = options;
    results.supersampling = temporal_supersampling(options.width, options.height, options.max_reference_side);
    Progress progress{options};
    for (const TemporalPath& path : paths) progress.total += static_cast<int>(path.poses.size()) + kStripFrames;
    for (const TemporalPath& path : paths) {
        std::vector<TemporalRow> rows = render_path(measurer, path, results.supersampling, progress);
        results.strips.push_back(render_strip(measurer, path, rows, results.supersampling, progress));
        results.paths.push_back(path.name);
        for (TemporalRow& row : rows) results.rows.push_back(std::move(row));
    }
    return results;
}

}  // namespace splat_lod::eval
