// splat_bake: trained splat scene → LOD asset (INRIA PLY with lod_level, coverage_min, coverage_max,
// or glTF with their _SPLAT_LOD_* attributes when the output ends in .glb or .gltf; coarse levels
// first). docs/algorithms.md §4.
//   splat_bake --input scene.ply --output scene.lod.ply [--capture auto|orbit|forward|world]
//              [--cameras auto|rings:RxA|grid:CxR[xD]|inside:RxA|orbit:N|cameras.json|path.json]
//              [--up X,Y,Z] [--forward X,Y,Z] [--width 512 --height 384] [--levels 4] [--size-threshold 2]
//              [--refine-iterations 200] [--refine-cameras 16] [--member-ranges|--no-member-ranges]
//              [--min-axis-ratio F] [--view-margin F] [--threads N] [--seed N]
// The capture shape (given, implied by a generated camera set or detected from a camera file) picks
// the cameras for "auto" and the defaults of the options the command line does not give
// (capture_defaults in splat_lod/bake/capture_shape.h); the log says which shape and why.
// The output is written only when the whole bake succeeded, through a temporary file in the same
// folder ("<output>.tmp-<pid>-<n>", synced to disk) and a rename (engine::write_file_atomic), so a
// failed or killed bake leaves any previous output byte for byte. A bake killed during that write
// leaves its temporary behind; the next successful bake to the same output removes it.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "engine/core/cli_values.h"
#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_lod/bake/bake.h"
#include "splat_lod/bake/bake_setup.h"
#include "splat_lod/bake/capture_shape.h"
#include "splat_lod/core/splat_io.h"

namespace {

struct Options {
    std::string input, output, cameras = "auto", capture = "auto", up = "0,1,0", forward, cells = "auto",
                               pooling = "mean";
    int width = 512;
    int height = 384;
    bool keep_ranges = false, no_member_ranges = false, single_file = false;
    splat_lod::bake::BakeOptions bake;
    splat_lod::bake::GivenSettings given;
};

// Fails before the (long) bake when the output cannot be written: its folder must exist and
// accept a new file. The probe file is removed again.
void check_output_writable(const std::filesystem::path& output, const std::filesystem::path& input) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(output, ec) && fs::is_directory(output, ec))
        engine::fail(output.string() + ": is a folder; give the output file's path");
    if (fs::exists(input, ec) && fs::exists(output, ec) && fs::equivalent(input, output, ec))
        engine::fail(output.string() + ": the output would replace the input; choose another file");
    const fs::path folder = output.parent_path().empty() ? fs::path(".") : output.parent_path();
    if (!fs::is_directory(folder, ec))
        engine::fail(output.string() + ": the folder " + folder.string() + " does not exist");
    const fs::path probe = folder / (".splat_bake_probe_" + std::to_string(::getpid()));
    std::FILE* file = std::fopen(probe.c_str(), "wb");
    if (file == nullptr) engine::fail(output.string() + ": cannot write in " + folder.string());
    std::fclose(file);
    fs::remove(probe, ec);
}

// The forward capture's settings in the log (`splat_bake: forward settings: …`).
void print_forward_settings(const splat_lod::bake::BakeOptions& b, std::size_t cameras) {
    std::fprintf(stderr,
                 "splat_bake: forward settings: %s pooling, %s, view margin %g, axis ratio >= %g, member ranges %s, "
                 "%zu of %zu cameras in the refinement\n",
                 b.pooling == splat_lod::bake::PoolingRule::moments ? "moments" : "mean",
                 b.choose_recipe                              ? "both cell recipes"
                 : b.cells == splat_lod::bake::CellRule::grid ? "grid cells"
                                                              : "adaptive cells",
                 b.view_margin, b.min_axis_ratio, b.member_ranges ? "on" : "off",
                 b.refine_cameras > 0 ? std::min(cameras, static_cast<std::size_t>(b.refine_cameras)) : cameras,
                 cameras);
}

// The bake cameras for the options and the scene (splat_lod::bake::prepare_bake); prints the capture
// shape and why, and applies its settings to those the command line did not give.
std::vector<splat_lod::reference::ReferenceCamera> prepare_cameras(Options& o, const splat_lod::SplatCloud& fine) {
    namespace bake = splat_lod::bake;
    bake::BakeSetup setup;
    setup.cameras = o.cameras;
    setup.capture = o.capture;
    setup.up = engine::parse_vec3(o.up, "--up");
    if (!o.forward.empty()) {
        setup.forward = engine::parse_vec3(o.forward, "--forward");
        if (!(glm::length(setup.forward) > 0.0f)) engine::fail("--forward: the direction must not be zero");
    }
    setup.width = o.width;
    setup.height = o.height;
    setup.options = o.bake;
    setup.given = o.given;
    bake::PreparedBake prepared = bake::prepare_bake(fine, setup);
    std::fprintf(stderr, "splat_bake: capture %s (%s)\n", bake::capture_shape_name(prepared.choice.shape),
                 prepared.choice.reason.c_str());
    std::fprintf(stderr, "splat_bake: %zu cameras (%s) at %dx%d\n", prepared.cameras.size(),
                 prepared.choice.spec.c_str(), o.width, o.height);
    o.bake = prepared.options;
    if (prepared.choice.shape == bake::CaptureShape::forward) print_forward_settings(o.bake, prepared.cameras.size());
    bake::validate(o.bake);
    return std::move(prepared.cameras);
}

int run(Options& o) {
    namespace bake = splat_lod::bake;
    check_output_writable(o.output, o.input);
    bake::validate(o.bake);

    const auto start = std::chrono::steady_clock::now();
    splat_lod::LoadReport report;
    const splat_lod::SplatCloud fine = splat_lod::load_splat_file(o.input, &report);
    std::fprintf(stderr, "splat_bake: %s: %zu Gaussians (%s, SH degree %d)", o.input.c_str(), fine.size(),
                 report.format.c_str(), fine.sh_degree);
    if (report.dropped() > 0) std::fprintf(stderr, ", %zu dropped (NaN/Inf or zero rotation)", report.dropped());
    std::fprintf(stderr, "\n");
    if (fine.empty()) engine::fail(o.input + ": the scene has no Gaussians to bake");
    if (const std::string why = splat_lod::bake::streamed_world_advice(fine); !why.empty() && !o.single_file)
        engine::fail(o.input + ": " + why + ": make it a streamed world instead, `splat_world --from " + o.input +
                     " --out <folder>` (docs/world_lod.md, \"Importing a capture\"), or give --single-file to bake "
                     "one file anyway");

    const auto cameras = prepare_cameras(o, fine);

    std::string last_stage;
    int last_percent = -1;
    o.bake.progress = [&](const std::string& stage, double fraction) {
        const int percent = static_cast<int>(fraction * 100.0);
        if (stage == last_stage && percent / 10 == last_percent / 10 && percent != 100) return;
        last_stage = stage;
        last_percent = percent;
        std::fprintf(stderr, "splat_bake: %-24s %3d%%\n", stage.c_str(), percent);
    };

    bake::BakeSummary summary;
    splat_lod::SplatCloud baked;
    try {
        baked = bake::bake_lod(fine, cameras, o.bake, &summary);
    } catch (const engine::Error& e) {
        engine::fail(o.input + ": " + e.what());
    }
    splat_lod::write_splat_file(o.output, baked);
    if (const std::size_t stale = engine::remove_stale_temporaries(o.output); stale > 0)
        std::fprintf(stderr, "splat_bake: removed %zu temporary file(s) of killed bakes beside %s\n", stale,
                     o.output.c_str());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stdout, "%s", bake::format_summary(summary).c_str());
    std::fprintf(stdout, "wrote %s (%zu Gaussians) in %.1f s\n", o.output.c_str(), baked.size(), seconds);
    const plugin_msgs::LodRule fades = plugin_msgs::LodRule{}.for_asset(baked.level_handover);
    std::fprintf(stdout,
                 "level handover: %s (the default transition placement, auto, fades its Gaussians placed %s over "
                 "%g octaves of coverage at each switch)\n",
                 splat_lod::level_handover_name(baked.level_handover),
                 std::string(plugin_msgs::to_string(fades.transition_placement)).c_str(),
                 static_cast<double>(fades.transition_band));
    return 0;
}

// The options that a capture shape decides, recorded as given or not after parsing.
struct ShapeOptions {
    CLI::Option *cells, *enlargement, *pooling, *margin, *axis_ratio, *member, *no_member, *refine_cameras;
};

void add_camera_options(CLI::App& app, Options& o) {
    app.add_option(
        "--cameras", o.cameras,
        "auto (the capture shape's set: rings:3x8 for orbit, grid:8x6x3 for forward, inside:2x8 for world), "
        "rings:RxA (R elevations x A azimuths around the scene), grid:CxR or grid:CxRxD (forward-facing: C x "
        "R eyes on the capture side looking along --forward, on D depth planes, default 2), inside:RxA (R "
        "rings of A eyes inside the scene looking out), orbit:N, an INRIA cameras.json or a camera-path "
        "JSON");
    app.add_option("--capture", o.capture,
                   "auto (detected from the cameras of a file, implied by a generated set, orbit for --cameras auto), "
                   "orbit (around an object), forward (a forward-facing sweep: moments pooling on adaptive cells, "
                   "axis ratio 0.3, member ranges, every camera refined) or world (cameras inside the content)")
        ->check(CLI::IsMember({"auto", "orbit", "forward", "world"}));
    app.add_option("--up", o.up, "the scene's up direction for generated cameras X,Y,Z (Y-down captures: 0,-1,0)");
    app.add_option("--forward", o.forward,
                   "view direction X,Y,Z of generated grid cameras (default: up x +X, i.e. 0,0,-1 for Y up and "
                   "0,0,1 for Y down)");
    app.add_option("--width", o.width, "bake camera width in pixels (refinement needs a multiple of 64)")
        ->check(CLI::Range(1, 16384));
    app.add_option("--height", o.height, "bake camera height in pixels (refinement needs a multiple of 64)")
        ->check(CLI::Range(1, 16384));
}

ShapeOptions add_bake_options(CLI::App& app, Options& o) {
    ShapeOptions shape{};
    app.add_option("--levels", o.bake.coarsest_level, "coarsest level to build (1..4)")->check(CLI::Range(1, 4));
    app.add_option("--size-threshold", o.bake.rule.size_threshold_px, "S_T in pixels");
    app.add_option("--refine-iterations", o.bake.refine_iterations, "Adam iterations per coarse level (0: off)")
        ->check(CLI::Range(0, 100000));
    shape.refine_cameras =
        app.add_option("--refine-cameras", o.bake.refine_cameras, "at most this many cameras for the refinement")
            ->check(CLI::Range(1, 10000));
    shape.enlargement = app.add_option("--max-enlargement", o.bake.max_enlargement,
                                       "clamp of the pooled Gaussians' enlargement S_T / S_avg (fixes the recipe)")
                            ->check(CLI::Range(1.0, 1000.0));
    shape.pooling = app.add_option("--pooling", o.pooling,
                                   "mean (docs/algorithms.md §4 steps 4-5) or moments (moment-matched cells)")
                        ->check(CLI::IsMember({"mean", "moments"}));
    shape.cells = app.add_option("--cells", o.cells,
                                 "auto (bake both recipes, keep the better), adaptive (the larger of grid and "
                                 "distance cells, enlargement <= 8) or grid (docs/algorithms.md §4 step 3, "
                                 "enlargement <= 32)")
                      ->check(CLI::IsMember({"auto", "adaptive", "grid"}));
    app.add_flag("--keep-ranges", o.keep_ranges, "do not measure the coverage ranges again after the refinement");
    shape.margin = app.add_option("--view-margin", o.bake.view_margin,
                                  "a camera sees a Gaussian whose centre is inside its image widened by this fraction "
                                  "of its size on every side (default 0)")
                       ->check(CLI::Range(0.0, 4.0));
    shape.axis_ratio = app.add_option("--min-axis-ratio", o.bake.min_axis_ratio,
                                      "raise every scale of a pooled Gaussian to at least this fraction of its largest "
                                      "(default 0; forward captures 0.3)")
                           ->check(CLI::Range(0.0, 1.0));
    shape.member = app.add_flag("--member-ranges", o.bake.member_ranges,
                                "cap each coarse Gaussian's coverage_max where its members stop being drawn (the "
                                "default for forward captures)");
    shape.no_member = app.add_flag("--no-member-ranges", o.no_member_ranges, "do not cap coverage_max by the members");
    app.add_option("--debug-images", o.bake.debug_image_dir,
                   "folder (existing) for the refinement's target/before/after PNGs of its first camera");
    app.add_option("--threads", o.bake.threads, "worker threads (0: all cores)")->check(CLI::Range(0, 1024));
    app.add_option("--seed", o.bake.seed, "seed of the refinement's camera order");
    return shape;
}

// The parsed options into the bake's settings.
void finish_options(Options& o, const ShapeOptions& shape) {
    o.bake.ranges_after_refine = !o.keep_ranges;
    o.bake.pooling =
        o.pooling == "moments" ? splat_lod::bake::PoolingRule::moments : splat_lod::bake::PoolingRule::mean;
    o.bake.cells = o.cells == "grid" ? splat_lod::bake::CellRule::grid : splat_lod::bake::CellRule::adaptive;
    o.bake.choose_recipe = o.cells == "auto" && shape.enlargement->count() == 0;
    if (shape.cells->count() > 0 && o.cells != "auto" && shape.enlargement->count() == 0)
        o.bake.max_enlargement = o.cells == "grid" ? 32.0 : 8.0;
    if (shape.member->count() > 0 && shape.no_member->count() > 0)
        engine::fail("--member-ranges and --no-member-ranges contradict each other");
    if (shape.no_member->count() > 0) o.bake.member_ranges = false;
    o.given = {shape.cells->count() > 0,         shape.enlargement->count() > 0,
               shape.pooling->count() > 0,       shape.margin->count() > 0,
               shape.axis_ratio->count() > 0,    shape.member->count() + shape.no_member->count() > 0,
               shape.refine_cameras->count() > 0};
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Bake levels of detail (multi-scale 3DGS) into a trained splat scene"};
    app.add_option("--input", o.input,
                   "trained scene (.ply, .compressed.ply, .splat, .spz, SOG meta.json, .glb, .gltf)")
        ->required();
    app.add_option("--output", o.output,
                   "LOD asset to write: INRIA PLY, or glTF (KHR_gaussian_splatting) for .glb/.gltf")
        ->required();
    app.add_flag("--single-file", o.single_file,
                 "bake one file even for a capture that a streamed world serves better (large or flat aerial)");
    add_camera_options(app, o);
    const ShapeOptions shape = add_bake_options(app, o);
    CLI11_PARSE(app, argc, argv);
    try {
        finish_options(o, shape);
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "splat_bake: %s\n", e.what());
        return 1;
    }
}
