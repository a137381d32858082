// splat_eval: speed against error, measured the same way for every method (docs/algorithms.md §6).
//   splat_eval --scene FILE | --scene-json FILE  --cameras orbit:N|cameras.json|path.json
//              --methods baseline,baseline_mip --sweep scale,distance,upscale --scales 1,2,4,...
//              --distances 1,2,4,... --out DIR [--width W --height H --frames 5 --warmup 2
//              --up X,Y,Z --name NAME --max-reference-side PX
//              --sheet-tile-width PX --sheet-methods a,b --chain lod-meta.json
//              --upscale-factors 2,3,4,8 --upscalers spline,bicubic,... --upscale-mode baseline
//              --temporal-frames 48 --temporal-path path.json
//              --temporal-paths dolly,orbit,walk,run,slow_dolly --metres-per-unit 1]
// Writes DIR/measurements.csv, report.md, the gnuplot PNGs, contact_sheet.png (scale sweep),
// levels.png (when `full` is measured) and upscale_crops.png (upscale sweep); progress on stderr.
// --chain adds each level of an existing LOD chain to the scale sweep as method chain_L<i>
// (baseline renderer, same views and references). The upscale sweep renders the splats at 1/f of
// the output and upscales them, against the native render of the same LOD mode. The temporal sweep
// (--sweep temporal) renders camera paths frame by frame and writes DIR/temporal.csv, temporal.md,
// temporal_<path>.png and temporal_strip_<path>.png (splat_lod/eval/temporal_sweep.h).
#include <cstdio>
#include <optional>

#include <CLI/CLI.hpp>

#include "engine/core/cli_values.h"
#include "engine/core/error.h"
#include "engine/engine.h"
#include "engine/platform/gl_context.h"
#include "splat_lod/eval/eval_report.h"
#include "splat_lod/eval/eval_run.h"
#include "splat_lod/eval/eval_scene.h"
#include "splat_lod/eval/frame_measurer.h"
#include "splat_lod/eval/lod_chain.h"
#include "splat_lod/eval/temporal_sweep.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"

namespace {

struct Options {
    std::string scene, scene_json, cameras = "orbit:2", methods = "baseline,baseline_mip", sweeps = "scale",
                                   scales = "1,2,4,8,16,32,64,128", distances = "1,2,4,8,16,32,64,128", out,
                                   up = "0,1,0", name, sheet_methods, chain, upscale_factors = "2,3,4,8",
                                   upscalers = "spline,bicubic,bilinear,lanczos3,spline_plain", temporal_path,
                                   temporal_paths = splat_lod::eval::kDefaultTemporalPaths;
    int temporal_frames = splat_lod::eval::kDefaultDollyFrames;
    double metres_per_unit = 1.0;
    bool temporal_frames_given = false, temporal_paths_given = false, metres_per_unit_given = false;
    bool temporal = false;  // --sweep names temporal
    splat_lod::eval::EvalOptions eval;
};

// A comma-separated list of scale, distance, upscale and temporal, run in its order (temporal last,
// as its own run: `temporal` is set instead of a sweep being listed); "both" is scale,distance.
std::vector<splat_lod::eval::Sweep> parse_sweeps(const std::string& text, bool& temporal) {
    using splat_lod::eval::Sweep;
    temporal = false;
    if (text == "both") return {Sweep::scale, Sweep::distance};
    std::vector<Sweep> sweeps;
    for (const std::string& name : splat_lod::eval::parse_name_list(text, "--sweep")) {
        if (name == "scale")
            sweeps.push_back(Sweep::scale);
        else if (name == "distance")
            sweeps.push_back(Sweep::distance);
        else if (name == "upscale")
            sweeps.push_back(Sweep::upscale);
        else if (name == "storage")
            sweeps.push_back(Sweep::storage);
        else if (name == "temporal")
            temporal = true;
        else
            engine::fail(
                "--sweep: expected scale, distance, upscale, storage, temporal (comma-separated) or both, got \"" +
                name + "\"");
    }
    return sweeps;
}

std::string default_name(const Options& o) {
    if (!o.name.empty()) return o.name;
    const std::filesystem::path path = o.scene.empty() ? o.scene_json : o.scene;
    // SOG scenes are folders with a meta.json: name them after the folder.
    return path.filename() == "meta.json" ? path.parent_path().filename().string() : path.stem().stem().string();
}

splat_lod::eval::TemporalOptions temporal_options(const Options& o) {
    splat_lod::eval::TemporalOptions t;
    t.scene_name = o.eval.scene_name;
    t.width = o.eval.width;
    t.height = o.eval.height;
    t.methods = o.eval.methods;
    t.max_reference_side = o.eval.max_reference_side;
    t.dolly_frames = o.temporal_frames;
    t.path_file = o.temporal_path;
    t.paths = o.temporal_paths;
    t.metres_per_unit = o.metres_per_unit;
    t.progress = o.eval.progress;
    return t;
}

// The options of the sweeps run, checked before anything is loaded or rendered.
void validate(const Options& o) {
    namespace eval = splat_lod::eval;
    if (!o.eval.sweeps.empty() || !o.temporal) eval::validate_options(o.eval);
    if (o.eval.sweeps.empty() && !o.chain.empty())
        engine::fail("--chain: comparison scenes are measured in the scale sweep, which is not run");
    if (o.temporal) {
        eval::validate_temporal_options(temporal_options(o));
        return;
    }
    if (!o.temporal_path.empty()) engine::fail("--temporal-path: only the temporal sweep (--sweep temporal) uses it");
    if (o.temporal_frames_given) engine::fail("--temporal-frames: only the temporal sweep (--sweep temporal) uses it");
    if (o.temporal_paths_given) engine::fail("--temporal-paths: only the temporal sweep (--sweep temporal) uses it");
    if (o.metres_per_unit_given) engine::fail("--metres-per-unit: only the temporal sweep (--sweep temporal) uses it");
}

// The temporal sweep's paths, made (and a --temporal-path file read) before anything is rendered.
std::vector<splat_lod::eval::TemporalPath> temporal_paths(const Options& o,
                                                          const std::vector<splat_lod::eval::CameraPose>& poses,
                                                          const splat_lod::eval::SceneExtent& extent) {
    if (!o.temporal) return {};
    if (poses.empty()) engine::fail("--cameras " + o.cameras + ": no camera for the dolly path");
    return splat_lod::eval::temporal_paths(temporal_options(o), poses.front(), extent,
                                           engine::parse_vec3(o.up, "--up"));
}

void run_temporal(const Options& o, splat_lod::eval::FrameMeasurer& measurer,
                  const std::vector<splat_lod::eval::TemporalPath>& paths, const std::string& renderer) {
    namespace eval = splat_lod::eval;
    const eval::TemporalResults results = eval::run_temporal_sweep(measurer, paths, temporal_options(o));
    eval::write_temporal_outputs(results, renderer, o.out);
    std::fprintf(stderr,
                 "splat_eval: temporal sweep of %s (%zu paths, reference supersampled %d\u00d7) written to %s\n",
                 o.eval.scene_name.c_str(), paths.size(), results.supersampling, o.out.c_str());
}

int run(Options& o) {
    namespace eval = splat_lod::eval;
    if (o.scene.empty() == o.scene_json.empty()) engine::fail("give exactly one of --scene and --scene-json");
    o.eval.methods = eval::select_methods(o.methods);
    o.eval.sweeps = parse_sweeps(o.sweeps, o.temporal);
    o.eval.scales = eval::parse_int_list(o.scales, "--scales");
    o.eval.distances = eval::parse_int_list(o.distances, "--distances");
    o.eval.upscale_factors = eval::parse_int_list(o.upscale_factors, "--upscale-factors");
    o.eval.upscalers = eval::select_upscalers(o.upscalers);
    o.eval.scene_name = default_name(o);
    o.eval.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
    if (!o.sheet_methods.empty()) o.eval.sheet_methods = eval::parse_name_list(o.sheet_methods, "--sheet-methods");
    // A chain level is placed like a splat file given with --scene; a scene JSON may move its
    // splats or add meshes, which the chain's files would not match.
    if (!o.chain.empty() && o.scene.empty()) engine::fail("--chain needs --scene (a splat file), not --scene-json");
    // The chain is read, and its level names checked with the other options, before anything is
    // loaded or rendered.
    const std::optional<eval::LodChain> chain =
        o.chain.empty() ? std::nullopt : std::optional<eval::LodChain>(eval::read_lod_chain(o.chain));
    if (chain) o.eval.comparisons = eval::chain_comparisons(*chain, o.scene, nullptr);
    validate(o);

    auto context = engine::HeadlessGlContext::create();
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    eval::EvalScene scene =
        o.scene.empty() ? eval::load_json_scene(engine, o.scene_json) : eval::load_splat_file_scene(o.scene);
    // Now the chain level held in the --scene file can share the loaded cloud.
    if (chain)
        o.eval.comparisons = eval::chain_comparisons(
            *chain, o.scene, scene.scene->components<splat_lod::SplatComponent>().front()->cloud);
    const auto poses = eval::load_camera_set(o.cameras, scene.extent, engine::parse_vec3(o.up, "--up"));
    const auto paths = temporal_paths(o, poses, scene.extent);

    eval::FrameMeasurer measurer(engine, *scene.scene);
    if (!o.eval.sweeps.empty()) {
        const eval::EvalResults results = eval::run_evaluation(measurer, poses, o.eval);
        eval::write_outputs(results, context->info().renderer, o.out);
        std::fprintf(stderr, "splat_eval: %zu measurements of %s written to %s\n", results.rows.size(),
                     o.eval.scene_name.c_str(), o.out.c_str());
    }
    if (o.temporal) run_temporal(o, measurer, paths, context->info().renderer);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Speed against error of splat rendering methods over scales and distances"};
    app.add_option("--scene", o.scene, "splat file (.ply, .compressed.ply, .splat, .spz, SOG meta.json, .glb, .gltf)");
    app.add_option("--scene-json", o.scene_json, "engine scene JSON with splat components");
    app.add_option("--cameras", o.cameras, "orbit:N, an INRIA cameras.json, or a camera-path JSON");
    app.add_option("--methods", o.methods,
                   "comma-separated methods (baseline, baseline_mip, filter_small, insert_large, full, full_hard)");
    app.add_option("--sweep", o.sweeps,
                   "comma-separated sweeps: scale, distance, upscale, storage, temporal (both: scale,distance)");
    app.add_option("--scales", o.scales, "downsampling factors per side; each must divide width and height");
    app.add_option("--distances", o.distances, "dolly factors for the distance and storage sweeps");
    app.add_option("--out", o.out, "output folder")->required();
    app.add_option("--width", o.eval.width, "full-resolution width")->check(CLI::Range(1, 16384));
    app.add_option("--height", o.eval.height, "full-resolution height")->check(CLI::Range(1, 16384));
    app.add_option("--frames", o.eval.frames, "timed frames per measurement")->check(CLI::Range(1, 1000));
    app.add_option("--warmup", o.eval.warmup, "warm-up frames before timing")->check(CLI::Range(0, 1000));
    app.add_option("--up", o.up, "the scene's up direction for orbit cameras X,Y,Z (Y-down captures: 0,-1,0)");
    app.add_option("--name", o.name, "scene name in the report (default: from the file name)");
    app.add_option("--max-reference-side", o.eval.max_reference_side,
                   "largest reference side of the distance and temporal sweeps")
        ->check(CLI::Range(1, 16384));
    app.add_option("--sheet-tile-width", o.eval.sheet_tile_width, "contact-sheet tile width (default: width / 4)")
        ->check(CLI::Range(1, 4096));
    app.add_option("--sheet-methods", o.sheet_methods,
                   "contact-sheet rows after the reference (default: every method of --methods; chain_L<i> allowed)");
    app.add_option("--chain", o.chain,
                   "an existing LOD chain's lod-meta.json: each level joins the scale sweep as chain_L<i>");
    app.add_option("--upscale-factors", o.upscale_factors,
                   "upscale sweep: render at 1/f of the output and upscale (integers >= 2)");
    app.add_option("--upscalers", o.upscalers,
                   "upscale sweep: spline, bicubic, bilinear, lanczos3, spline_plain (spline, plain dilation)");
    app.add_option("--upscale-mode", o.eval.upscale_mode,
                   "upscale sweep: the LOD method of native and upscaled renders (baseline, full, ...)");
    app.add_option("--temporal-frames", o.temporal_frames,
                   "temporal sweep: frames of the dolly path, out to 64x the first view's distance and back (>= 4)");
    app.add_option("--temporal-path", o.temporal_path,
                   "temporal sweep: a camera-path JSON or INRIA cameras.json, one more path named by its stem");
    app.add_option("--temporal-paths", o.temporal_paths,
                   "temporal sweep: the generated paths, in this order (some of dolly,orbit,walk,run,slow_dolly)");
    app.add_option("--metres-per-unit", o.metres_per_unit,
                   "temporal sweep: the scene's scale, for the walk (1.4 m/s) and run (5 m/s) paths at 60 fps");
    CLI11_PARSE(app, argc, argv);
    o.temporal_frames_given = app.count("--temporal-frames") > 0;
    o.temporal_paths_given = app.count("--temporal-paths") > 0;
    o.metres_per_unit_given = app.count("--metres-per-unit") > 0;
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "splat_eval: %s\n", e.what());
        return 1;
    }
}
