#include "splat_lod/eval/eval_run.h"

#include <algorithm>

#include "engine/core/error.h"
#include "splat_lod/eval/frame_measurer.h"
#include "splat_lod/eval/image_metrics.h"

namespace splat_lod::eval {
namespace {

struct Progress {
    const EvalOptions& options;
    int total = 0;
    int done = 0;

    void step(int view, const std::string& method, int factor, Sweep sweep) {
        ++done;
        if (!options.progress) return;
        // Appended piece by piece: GCC 12 warns falsely on "[" + std::string when inlined.
        std::string line = "[";
        line += std::to_string(done) + "/" + std::to_string(total) + "] " + options.scene_name;
        line += " view ";
        line += std::to_string(view) + " " + method + " " + std::to_string(factor) + "\u00d7 (";
        line += sweep_name(sweep);
        line += ")";
        options.progress(line);
    }
};

Measurement make_row(const EvalOptions& o, Sweep sweep, int view, const CameraPose& pose, const std::string& method,
                     int factor, const FrameMeasurement& m) {
    Measurement row;
    row.scene = o.scene_name;
    row.sweep = sweep;
    row.view = view;
    row.view_name = pose.name;
    row.method = method;
    row.factor = factor;
    row.width = m.image.width;
    row.height = m.image.height;
    row.wall_ms = m.wall_ms;
    row.gpu_ms = m.gpu_ms;
    row.statistics = m.statistics;
    return row;
}

void score(Measurement& row, const FloatImage& reference, const engine::Image& image) {
    const FloatImage rendered = to_float(image);
    row.psnr = psnr(rendered, reference);
    row.ssim = ssim(rendered, reference);
}

// One view's references of the scale sweep: scale k → the full-resolution baseline area-averaged by k.
using References = std::map<int, FloatImage>;

bool fits_scale(int k, int width, int height) {
    return k >= 1 && k <= width && k <= height && width % k == 0 && height % k == 0;
}

bool measures(const EvalOptions& o, const std::string& method) {
    return std::any_of(o.methods.begin(), o.methods.end(), [&](const Method& m) { return m.name == method; });
}

// Untimed single frames of the first view: where `full` draws which level.
void level_picture(FrameMeasurer& measurer, const CameraPose& pose, EvalResults& results) {
    const EvalOptions& o = results.options;
    for (int k : kLevelPictureScales)
        if (fits_scale(k, o.width, o.height))
            results.level_tiles.push_back(
                {"full", k, measurer.render(level_colouring_method(), make_view(pose, o.width / k, o.height / k))});
}

References scale_sweep(FrameMeasurer& measurer, const CameraPose& pose, int view, Progress& progress,
                       EvalResults& results) {
    const EvalOptions& o = results.options;
    const FloatImage full = to_float(measurer.render(truth_method(), make_view(pose, o.width, o.height)));
    References references;
    for (int k : o.scales) {
        references[k] = area_average(full, k);
        if (view == 0) results.tiles.push_back({"reference", k, to_rgba8(references[k])});
    }
    for (const Method& method : o.methods)
        for (int k : o.scales) {
            progress.step(view, method.name, k, Sweep::scale);
            FrameMeasurement m =
                measurer.measure(method, make_view(pose, o.width / k, o.height / k), o.frames, o.warmup);
            if (view == 0) results.tiles.push_back({method.name, k, m.image});
            Measurement row = make_row(o, Sweep::scale, view, pose, method.name, k, m);
            score(row, references[k], m.image);
            results.rows.push_back(std::move(row));
        }
    if (view == 0 && measures(o, "full")) level_picture(measurer, pose, results);
    return references;
}

// A comparison scene at every view and scale, drawn by the same engine (the splat pass uploads
// the scene it is given) and scored against the main scene's references.
void comparison_sweep(FrameMeasurer& main, const ComparisonScene& comparison, const std::vector<CameraPose>& poses,
                      const std::vector<References>& references, Progress& progress, EvalResults& results) {
    const EvalOptions& o = results.options;
    if (!comparison.load) engine::fail("comparison scene \"" + comparison.method + "\": nothing to load");
    const EvalScene scene = comparison.load();
    FrameMeasurer measurer(main.engine(), *scene.scene);
    for (std::size_t v = 0; v < poses.size(); ++v)
        for (int k : o.scales) {
            const int view = static_cast<int>(v);
            progress.step(view, comparison.method, k, Sweep::scale);
            FrameMeasurement m = measurer.measure(reference_method(), make_view(poses[v], o.width / k, o.height / k),
                                                  o.frames, o.warmup);
            if (view == 0) results.tiles.push_back({comparison.method, k, m.image});
            Measurement row = make_row(o, Sweep::scale, view, poses[v], comparison.method, k, m);
            score(row, references[v].at(k), m.image);
            results.rows.push_back(std::move(row));
        }
}

void distance_sweep(FrameMeasurer& measurer, const CameraPose& pose, int view, Progress& progress,
                    EvalResults& results) {
    const EvalOptions& o = results.options;
    for (int d : o.distances) {
        const CameraPose far = dolly(pose, static_cast<float>(d));
        std::optional<FloatImage> reference;
        if (d * o.width <= o.max_reference_side && d * o.height <= o.max_reference_side) {
            reference =
                area_average(to_float(measurer.render(truth_method(), make_view(far, d * o.width, d * o.height))), d);
            results.max_reference_distance = std::max(results.max_reference_distance, d);
        }
        for (const Method& method : o.methods) {
            progress.step(view, method.name, d, Sweep::distance);
            FrameMeasurement m = measurer.measure(method, make_view(far, o.width, o.height), o.frames, o.warmup);
            Measurement row = make_row(o, Sweep::distance, view, pose, method.name, d, m);
            if (reference) score(row, *reference, m.image);
            results.rows.push_back(std::move(row));
        }
    }
}

// The upscale sweep at one view: a native reference frame, the native render measured (and scored
// against that reference: the renderer is deterministic, so this is exact), then every factor and
// upscaler at the output size against the reference.
void upscale_sweep(FrameMeasurer& measurer, const CameraPose& pose, int view, Progress& progress,
                   EvalResults& results) {
    const EvalOptions& o = results.options;
    const Method& mode = find_method(o.upscale_mode, "--upscale-mode");
    const engine::CameraView camera = make_view(pose, o.width, o.height);
    const Method native = native_method(mode);
    const FloatImage reference = to_float(measurer.render(native, camera));
    const std::vector<int> crop_factors = upscale_crop_factors(o);
    const auto keep_tile = [&](int factor) {
        return view == 0 &&
               (factor == 1 || std::find(crop_factors.begin(), crop_factors.end(), factor) != crop_factors.end());
    };

    const auto measure = [&](const Method& method, int factor) {
        progress.step(view, method.name, factor, Sweep::upscale);
        FrameMeasurement m = measurer.measure(method, camera, o.frames, o.warmup);
        Measurement row = make_row(o, Sweep::upscale, view, pose, method.name, factor, m);
        score(row, reference, m.image);
        results.rows.push_back(std::move(row));
        if (keep_tile(factor)) results.upscale_tiles.push_back({method.name, factor, std::move(m.image)});
    };
    measure(native, 1);
    for (int f : o.upscale_factors)
        for (const UpscalerVariant& variant : o.upscalers) measure(upscaled_method(mode, variant, f), f);
}

// The storage sweep at one view: every method at every distance of --distances drawn from the scene
// stored as full floats (the reference: the trained values) and from the compact storage, which is
// measured and scored against it (docs/gpu_storage.md).
void storage_sweep(FrameMeasurer& measurer, const CameraPose& pose, int view, Progress& progress,
                   EvalResults& results) {
    const EvalOptions& o = results.options;
    for (int d : o.distances) {
        const engine::CameraView camera = make_view(dolly(pose, static_cast<float>(d)), o.width, o.height);
        for (const Method& method : o.methods) {
            progress.step(view, method.name, d, Sweep::storage);
            const FloatImage reference = to_float(measurer.render(stored_as(method, GpuStorage::full), camera));
            FrameMeasurement m = measurer.measure(stored_as(method, GpuStorage::compact), camera, o.frames, o.warmup);
            Measurement row = make_row(o, Sweep::storage, view, pose, method.name, d, m);
            score(row, reference, m.image);
            results.rows.push_back(std::move(row));
        }
    }
}

void validate_upscale_options(const EvalOptions& o) {
    if (o.upscale_factors.empty()) engine::fail("--upscale-factors: no factor given");
    for (std::size_t i = 0; i < o.upscale_factors.size(); ++i) {
        const int f = o.upscale_factors[i];
        const std::string factor = std::string("--upscale-factors: factor ") + std::to_string(f);
        if (f < 2) engine::fail(factor + " is no upscaling (factors must be integers \u2265 2)");
        if (std::find(o.upscale_factors.begin(), o.upscale_factors.begin() + static_cast<std::ptrdiff_t>(i), f) !=
            o.upscale_factors.begin() + static_cast<std::ptrdiff_t>(i))
            engine::fail(factor + " is listed twice");
        const int w = upscale_source_side(o.width, f), h = upscale_source_side(o.height, f);
        if (w < kMinUpscaleSource || h < kMinUpscaleSource)
            engine::fail(factor + " is too large for " + std::to_string(o.width) + "\u00d7" + std::to_string(o.height) +
                         ": it renders " + std::to_string(w) + "\u00d7" + std::to_string(h) + " pixels, fewer than " +
                         std::to_string(kMinUpscaleSource) + " per side");
    }
    if (o.upscalers.empty()) engine::fail("--upscalers: no upscaler given");
    for (std::size_t i = 0; i < o.upscalers.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (o.upscalers[i].name == o.upscalers[j].name)
                engine::fail("--upscalers: \"" + o.upscalers[i].name + "\" is listed twice");
    find_method(o.upscale_mode, "--upscale-mode");
}

bool runs(const EvalOptions& o, Sweep sweep) {
    return std::find(o.sweeps.begin(), o.sweeps.end(), sweep) != o.sweeps.end();
}

std::size_t measurements_per_view(const EvalOptions& o, Sweep sweep) {
    switch (sweep) {
        case Sweep::scale:
            return measured_methods(o, sweep).size() * o.scales.size();
        case Sweep::distance:
        case Sweep::storage:
            return o.methods.size() * o.distances.size();
        case Sweep::upscale:
            return 1 + o.upscale_factors.size() * o.upscalers.size();
    }
    return 0;
}

}  // namespace

const char* sweep_name(Sweep sweep) {
    switch (sweep) {
        case Sweep::scale:
            return "scale";
        case Sweep::distance:
            return "distance";
        case Sweep::upscale:
            return "upscale";
        case Sweep::storage:
            return "storage";
    }
    return "?";
}

std::vector<int> upscale_crop_factors(const EvalOptions& o) {
    std::vector<int> factors;
    for (int f : {3, 4})
        if (std::find(o.upscale_factors.begin(), o.upscale_factors.end(), f) != o.upscale_factors.end())
            factors.push_back(f);
    if (factors.empty() && !o.upscale_factors.empty()) factors.push_back(o.upscale_factors.front());
    return factors;
}

std::vector<std::string> measured_methods(const EvalOptions& o, Sweep sweep) {
    std::vector<std::string> names;
    if (sweep == Sweep::upscale) {
        names.push_back("native");
        for (const UpscalerVariant& variant : o.upscalers) names.push_back(variant.name);
        return names;
    }
    for (const Method& method : o.methods) names.push_back(method.name);
    if (sweep == Sweep::scale)
        for (const ComparisonScene& comparison : o.comparisons) names.push_back(comparison.method);
    return names;
}

void validate_options(const EvalOptions& o) {
    if (o.width < 1 || o.height < 1) engine::fail("--width/--height: the image size must be positive");
    if (o.frames < 1) engine::fail("--frames: at least one timed frame is needed");
    if (o.warmup < 0) engine::fail("--warmup: must not be negative");
    if (o.sweeps.empty()) engine::fail("--sweep: no sweep given");
    if ((runs(o, Sweep::scale) || runs(o, Sweep::distance) || runs(o, Sweep::storage)) && o.methods.empty())
        engine::fail("--methods: no method given");
    if (runs(o, Sweep::scale))
        for (int k : o.scales) check_scale(k, o.width, o.height, "--scales");
    for (int d : o.distances)
        if (d < 1) engine::fail("--distances: distance " + std::to_string(d) + " is not a positive integer");
    if (runs(o, Sweep::upscale)) validate_upscale_options(o);
    if (!o.comparisons.empty() && !runs(o, Sweep::scale))
        engine::fail("--chain: comparison scenes are measured in the scale sweep, which is not run");
    std::vector<std::string> names;
    for (const Method& method : o.methods) names.push_back(method.name);
    for (const ComparisonScene& comparison : o.comparisons) {
        if (std::find(names.begin(), names.end(), comparison.method) != names.end())
            engine::fail("comparison scene \"" + comparison.method + "\": another method has that name");
        names.push_back(comparison.method);
    }
    for (const std::string& row : o.sheet_methods)
        if (row != "reference" && std::find(names.begin(), names.end(), row) == names.end()) {
            std::string known = "reference";
            for (const auto& name : names) known += ", " + name;
            engine::fail("--sheet-methods: \"" + row + "\" is not measured (measured: " + known + ")");
        }
}

EvalResults run_evaluation(FrameMeasurer& measurer, const std::vector<CameraPose>& poses, const EvalOptions& options) {
    validate_options(options);
    EvalResults results;
    results.options = options;
    results.views = static_cast<int>(poses.size());
    Progress progress{options};
    for (Sweep sweep : options.sweeps)
        progress.total += static_cast<int>(poses.size() * measurements_per_view(options, sweep));
    // The comparison scenes need every view's references after the main scene's sweeps; kept only then.
    std::vector<References> references;
    for (Sweep sweep : options.sweeps)
        for (std::size_t v = 0; v < poses.size(); ++v) {
            if (sweep == Sweep::distance) {
                distance_sweep(measurer, poses[v], static_cast<int>(v), progress, results);
                continue;
            }
            if (sweep == Sweep::upscale) {
                upscale_sweep(measurer, poses[v], static_cast<int>(v), progress, results);
                continue;
            }
            if (sweep == Sweep::storage) {
                storage_sweep(measurer, poses[v], static_cast<int>(v), progress, results);
                continue;
            }
            References view_references = scale_sweep(measurer, poses[v], static_cast<int>(v), progress, results);
            if (!options.comparisons.empty()) references.push_back(std::move(view_references));
        }
    for (const ComparisonScene& comparison : options.comparisons)
        comparison_sweep(measurer, comparison, poses, references, progress, results);
    return results;
}

}  // namespace splat_lod::eval
