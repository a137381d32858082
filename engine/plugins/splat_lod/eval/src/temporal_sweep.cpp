// The temporal sweep's rendering (splat_lod/eval/temporal_sweep.h): every path frame by frame, the
// reference first, then every method; only the previous frame of each is kept, and the frames of
// each path's strip are rendered again once its peak is known (the renderer is deterministic).
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

std::vector<TemporalRow> render_path(FrameMeasurer& measurer, const TemporalPath& path, int s, Progress& progress) {
    const TemporalOptions& o = progress.options;
    std::vector<TemporalRow> rows(o.methods.size());
    std::vector<FloatImage> previous(o.methods.size());
    FloatImage reference_previous;
    for (std::size_t t = 0; t < path.poses.size(); ++t) {
        progress.step(path.name, "frame " + std::to_string(t));
        FloatImage reference = reference_frame(measurer, path.poses[t], o, s);
        const engine::CameraView view = make_view(path.poses[t], o.width, o.height);
        for (std::size_t m = 0; m < o.methods.size(); ++m) {
            const FrameMeasurement measured = measurer.measure(o.methods[m], view, 1, 0);
            FloatImage image = to_float(measured.image);
            TemporalRow& row = rows[m];
            row.psnr.push_back(psnr(image, reference));
            if (const auto it = measured.gpu_ms.find("splat"); it != measured.gpu_ms.end())
                row.splat_ms.push_back(it->second);
            if (t > 0) {
                row.pair_errors.push_back(temporal_pair_error(previous[m], image, reference_previous, reference));
                row.pair_pops.push_back(temporal_pair_pop(previous[m], image, reference_previous, reference));
            }
            previous[m] = std::move(image);
        }
        reference_previous = std::move(reference);
    }
    for (std::size_t m = 0; m < rows.size(); ++m) {
        TemporalRow& row = rows[m];
        row.method = o.methods[m].name;
        row.path = path.name;
        row.frames = static_cast<int>(path.poses.size());
        row.temporal_error = mean(row.pair_errors);
        row.pop_mean = mean(row.pair_pops);
        row.pop_peak = row.pair_pops.empty() ? 0.0 : *std::max_element(row.pair_pops.begin(), row.pair_pops.end());
        row.psnr_mean = mean(row.psnr);
        if (!row.splat_ms.empty()) row.splat_ms_mean = mean(row.splat_ms);
    }
    return rows;
}

// The method and pair with the largest pop of a path (the first where several tie).
void find_peak(const std::vector<TemporalRow>& rows, TemporalStrip& strip) {
    strip.peak_pop = -1.0;
    for (const TemporalRow& row : rows)
        for (std::size_t i = 0; i < row.pair_pops.size(); ++i)
            if (row.pair_pops[i] > strip.peak_pop) {
                strip.peak_pop = row.pair_pops[i];
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
    std::vector<FloatImage> reference, peak;
    for (int c = 0; c < kStripFrames; ++c) {
        const int t = strip.first_frame + c;
        progress.step(path.name, "strip frame " + std::to_string(t));
        const CameraPose& pose = path.poses[static_cast<std::size_t>(t)];
        reference.push_back(reference_frame(measurer, pose, o, s));
        strip.images[0].push_back(to_rgba8(reference.back()));
        for (std::size_t m = 0; m < o.methods.size(); ++m) {
            strip.images[m + 1].push_back(measurer.render(o.methods[m], make_view(pose, o.width, o.height)));
            if (o.methods[m].name == strip.peak_method) peak.push_back(to_float(strip.images[m + 1].back()));
        }
    }
    for (int c = 1; c < kStripFrames; ++c) {
        const auto i = static_cast<std::size_t>(c);
        strip.differences.push_back(
            temporal_difference_image(peak[i - 1], peak[i], reference[i - 1], reference[i], kStripDifferenceGain));
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
