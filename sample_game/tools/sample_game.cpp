// sample_game: the streamed outdoor walkthrough (sample_game/README.md).
//   sample_game [--world DIR]                                  a window: fly or follow the path
//   sample_game --profile [--world DIR] [--out DIR] [--width W --height H] [--frames N]
//               [--memory-budget-mib M] [--upload-budget-mib U] [--frames-png K]
//               [--no-baseline] [--baseline-every K] [--baseline-overview-every K] [--no-preload]
//               [--sync-streaming] [LOD options]
//   sample_game --soak [--world DIR] [--out DIR] [--laps N] [--frames N] [--no-faults] [--retry-after-frames N]
//   sample_game --reference [--world DIR] [--width W --height H] [--frames N] [--fov-y D] [--supersample S] [--force]
// The profile runs headless (EGL): the path with LOD and streaming, then the baseline, and writes
// profile.csv, baseline.csv, summary.txt, plots and frames to --out; it prints the summary. Exit
// code 1 on an error (bad option, missing or broken world, no GL); a budget check that fails is a
// result, printed in the summary, not an error. The soak (soak_run.h) walks the path --laps times
// (--frames poses per lap), damaging chunk files of a linked copy of the world on the middle laps,
// and exits 1 when a check fails (a leak, a chunk that does not come back). The reference
// (reference_run.h) renders the profile's reference frames supersampled and caches them beside
// the world, where the profile with the same size, frames and field of view finds them.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "engine/core/error.h"
#include "engine/platform/gl_context.h"
#include "sample_game/game_window.h"
#include "sample_game/path_file.h"
#include "sample_game/profile_run.h"
#include "sample_game/reference_run.h"
#include "sample_game/soak_run.h"
#include "sample_game/world_path.h"

namespace {

struct CommandLine {
    bool profile = false, soak = false, no_faults = false, reference = false, force = false;
    int supersample = sample_game::kDefaultReferenceSupersample;
    int laps = 10;
    std::string world = "out/world/default", out = "out/game";
    int width = 0, height = 0, frames = -1;
    double memory_budget_mib = -1.0, upload_budget_mib = -1.0;
    std::string mode, upscaler;
    sample_game::GameSettings settings;
    int frames_png = 0, baseline_every = 10, baseline_overview_every = 1, path_frames = 1800;
    bool no_baseline = false, no_preload = false, no_ui = false;
    std::string screenshot, offscreen, write_path;
};

template <typename E, std::size_t N>
E enum_named(const std::array<std::string_view, N>& names, const std::string& text) {
    for (std::size_t i = 0; i < N; ++i)
        if (names[i] == text) return static_cast<E>(i);
    return static_cast<E>(0);  // unreachable: CLI::IsMember checked the name
}

// The LOD rule and raster options (renderer and streamer alike).
void add_lod_options(CLI::App& app, CommandLine& c) {
    auto& lod = c.settings.lod;
    app.add_option("--lod-mode", c.mode, "LOD selection mode (plugin_msgs::LodMode; default full)")
        ->check(CLI::IsMember(
            std::vector<std::string>(plugin_msgs::kLodModeNames.begin(), plugin_msgs::kLodModeNames.end())));
    app.add_option("--lod-size-threshold", lod.rule.size_threshold_px, "S_T in pixels")->capture_default_str();
    app.add_option("--lod-rel-min", lod.rule.rel_min, "S_rel_min")->capture_default_str();
    app.add_option("--lod-rel-max", lod.rule.rel_max, "S_rel_max")->capture_default_str();
    app.add_option("--lod-transition-band", lod.rule.transition_band,
                   "Octaves of coverage over which a Gaussian fades into its coarser level (0: hard switching)")
        ->capture_default_str();
    app.add_option("--render-scale", lod.render_scale, "Splat raster resolution relative to the output, (0, 1]")
        ->capture_default_str();
    app.add_option("--upscaler", c.upscaler, "spline (default), bicubic, bilinear or lanczos3")
        ->check(CLI::IsMember({"spline", "bicubic", "bilinear", "lanczos3"}));
    app.add_flag("--level-colouring", lod.level_colouring, "Tint each Gaussian by its LOD level");
    app.add_option("--splat-budget", lod.splat_budget,
                   "At most N Gaussians drawn per frame (0: none); above it the LOD cut moves to coarser levels")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
}

// What to run headless: the profile, the soak or the reference, and their own settings.
void add_mode_options(CLI::App& app, CommandLine& c) {
    app.add_flag("--profile", c.profile,
                 "Run headless: the path with LOD + streaming, then the baseline; write CSV, plots, summary");
    app.add_flag("--soak", c.soak,
                 "Run headless: walk the path --laps times, damaging chunk files of a copy of the world; check "
                 "that memory and GL objects stay flat and streaming recovers");
    app.add_flag("--reference", c.reference,
                 "Run headless: render the profile's reference frames supersampled (baseline mode, every chunk "
                 "resident) and cache them in <world>/reference/, where --profile finds them");
    app.add_flag("--force", c.force, "Reference: make it again even when it is cached");
    app.add_option("--supersample", c.supersample,
                   "Reference: pixels per side rendered for each output pixel (3..8; the profile looks for this "
                   "factor's reference)")
        ->check(CLI::Range(3, 8))
        ->capture_default_str();
    app.add_option("--laps", c.laps, "Soak: laps of the path (default 10)")->check(CLI::Range(2, 100000));
    app.add_flag("--no-faults", c.no_faults, "Soak: leave the chunk files alone (stream the world itself)");
}

// The streamer: budgets, retries, load distances, the chunk groups' switch, the GPU's SH degree.
void add_streaming_options(CLI::App& app, CommandLine& c) {
    app.add_option("--retry-after-frames", c.settings.retry_failed_after_frames,
                   "Try a chunk that failed to load again after N frames (0: never)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--memory-budget-mib", c.memory_budget_mib, "Streamed GPU memory budget (default 384)")
        ->check(CLI::Range(0.01, 1e6));
    app.add_option("--upload-budget-mib", c.upload_budget_mib, "Upload budget per frame (default 8)")
        ->check(CLI::Range(0.01, 1e5));
    app.add_flag("--sync-streaming", c.settings.sync_streaming,
                 "Read chunks inside each update (deterministic; tests)");
    app.add_option("--load-distance-scale", c.settings.load_distance_scale,
                   "Load levels this much earlier than the on-axis bound")
        ->capture_default_str();
    app.add_option("--group-cell-px", c.settings.group_cell_px,
                   "Draw a chunk group instead of its chunks where its cell is at most this many pixels (0: never)")
        ->check(CLI::Range(0.0, 1000.0))
        ->capture_default_str();
    app.add_option("--fade-frames", c.settings.fade_frames,
                   "Updates over which a chunk, group or arriving level fades in or out (0: at once)")
        ->check(CLI::Range(0, 1000))
        ->capture_default_str();
    app.add_option("--anticipate", c.settings.anticipation_updates,
                   "Updates ahead that the cut anticipates the moving camera by (0: not at all)")
        ->check(CLI::Range(0, 1000))
        ->capture_default_str();
    app.add_option("--sh-degree", c.settings.sh_degree, "SH degree stored on the GPU (the generated world has 0)")
        ->check(CLI::Range(0, 3))
        ->capture_default_str();
}

// The profile's baseline run, frames written and preload.
void add_profile_options(CLI::App& app, CommandLine& c) {
    app.add_option("--frames-png", c.frames_png,
                   "Profile: write every K-th frame as PNG, and a contact sheet (0: none)")
        ->check(CLI::NonNegativeNumber);
    app.add_flag("--no-baseline", c.no_baseline, "Profile: skip the baseline run (no overview ratio)");
    app.add_option("--baseline-every", c.baseline_every,
                   "Profile: baseline frames outside the overview, every K-th (0: none)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--baseline-overview-every", c.baseline_overview_every,
                   "Profile: baseline on every K-th overview frame")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_flag("--no-preload", c.no_preload,
                 "Profile: start the walk cold instead of streaming the first view first");
}

void add_options(CLI::App& app, CommandLine& c) {
    add_mode_options(app, c);
    add_streaming_options(app, c);
    add_profile_options(app, c);
    app.add_option("--world", c.world, "The world's folder (world.json; made by splat_world)")->capture_default_str();
    app.add_option("--out", c.out, "Profile output folder (the soak's default is out/soak)")->capture_default_str();
    app.add_option("--width", c.width, "Image width (profile default 640, window 1280)")->check(CLI::Range(16, 16384));
    app.add_option("--height", c.height, "Image height (profile default 360, window 720)")
        ->check(CLI::Range(16, 16384));
    app.add_option(
           "--frames", c.frames,
           "Profile: poses along the path (default 400); soak: per lap (default 200); window: quit after N frames")
        ->check(CLI::PositiveNumber);
    add_lod_options(app, c);
    app.add_option("--fov-y", c.settings.fov_y_deg, "Vertical field of view in degrees")->capture_default_str();
    app.add_option("--path", c.settings.path_file,
                   "Walk this path instead of the world's own: a JSON list of poses (one per frame) or keys "
                   "(sampled over --frames); see sample_game/README.md");
    app.add_option("--write-path", c.write_path,
                   "Write the world's path over --frames poses (or --path's) as a poses file and exit");
    app.add_option("--path-frames", c.path_frames, "Window: poses of the looping path")
        ->check(CLI::Range(10, 1000000))
        ->capture_default_str();
    app.add_option("--screenshot", c.screenshot, "Window: after the last --frames frame, write the window as PNG");
    app.add_option("--offscreen", c.offscreen, "Window: also write the frame without overlay as PNG");
    app.add_flag("--no-ui", c.no_ui, "Window: start with the overlay hidden (F1 toggles it)");
}

void apply_common(CommandLine& c) {
    if (!c.mode.empty())
        c.settings.lod.rule.mode = enum_named<plugin_msgs::LodMode>(plugin_msgs::kLodModeNames, c.mode);
    if (!c.upscaler.empty())
        c.settings.lod.upscaler = enum_named<plugin_msgs::Upscaler>(plugin_msgs::kUpscalerNames, c.upscaler);
    if (c.memory_budget_mib > 0.0)
        c.settings.memory_budget_bytes =
            static_cast<std::uint64_t>(c.memory_budget_mib * static_cast<double>(sample_game::kMiB));
    if (c.upload_budget_mib > 0.0)
        c.settings.upload_budget_bytes =
            static_cast<std::uint64_t>(c.upload_budget_mib * static_cast<double>(sample_game::kMiB));
}

int run_profile(const CommandLine& c) {
    sample_game::ProfileOptions o;
    o.world = c.world;
    o.out = c.out;
    o.width = c.width > 0 ? c.width : 640;
    o.height = c.height > 0 ? c.height : 360;
    o.frames = c.frames > 0 ? c.frames : 400;
    o.settings = c.settings;
    o.frames_png_every = c.frames_png;
    o.baseline = !c.no_baseline;
    o.baseline_every = c.baseline_every;
    o.baseline_overview_every = c.baseline_overview_every;
    o.preload = !c.no_preload;
    o.reference_supersample = c.supersample;
    sample_game::validate(o);  // before making a GL context: option errors come first
    const auto context = engine::HeadlessGlContext::create();
    std::fprintf(stderr, "sample_game: %s on %s\n", context->info().renderer.c_str(), context->info().platform.c_str());
    const sample_game::ProfileOutcome outcome = sample_game::run_profile(o, stderr);
    std::printf("%s", outcome.summary_text.c_str());
    if (!outcome.plot_problem.empty()) std::fprintf(stderr, "sample_game: %s\n", outcome.plot_problem.c_str());
    return 0;
}

int run_reference(const CommandLine& c) {
    sample_game::ReferenceOptions o;  // the profile's defaults, so that the profile finds it
    o.world = c.world;
    o.width = c.width > 0 ? c.width : 640;
    o.height = c.height > 0 ? c.height : 360;
    o.frames = c.frames > 0 ? c.frames : 400;
    o.settings = c.settings;
    o.supersample = c.supersample;
    o.force = c.force;
    sample_game::validate(o);
    const auto context = engine::HeadlessGlContext::create();
    std::fprintf(stderr, "sample_game: %s on %s\n", context->info().renderer.c_str(), context->info().platform.c_str());
    const sample_game::ReferenceOutcome outcome = sample_game::make_reference(o, stderr);
    std::printf("%s", outcome.text.c_str());
    return 0;
}

int run_soak(const CommandLine& c) {
    sample_game::SoakOptions o;
    o.world = c.world;
    o.out = c.out == "out/game" ? "out/soak" : c.out;
    o.width = c.width > 0 ? c.width : 320;
    o.height = c.height > 0 ? c.height : 180;
    o.frames_per_lap = c.frames > 0 ? c.frames : 200;
    o.laps = c.laps;
    o.faults = !c.no_faults;
    o.settings = c.settings;
    sample_game::validate(o);
    const auto context = engine::HeadlessGlContext::create();
    std::fprintf(stderr, "sample_game: %s on %s\n", context->info().renderer.c_str(), context->info().platform.c_str());
    const sample_game::SoakOutcome outcome = sample_game::run_soak(o, stderr);
    std::printf("%s", outcome.summary_text.c_str());
    return outcome.passed ? 0 : 1;
}

int run_window(const CommandLine& c) {
    sample_game::WindowOptions o;
    o.world = c.world;
    o.width = c.width > 0 ? c.width : 1280;
    o.height = c.height > 0 ? c.height : 720;
    o.settings = c.settings;
    o.path_frames = c.path_frames;
    o.frames = c.frames > 0 ? c.frames : 0;
    o.screenshot = c.screenshot;
    o.offscreen = c.offscreen;
    o.no_ui = c.no_ui;
    if ((!o.screenshot.empty() || !o.offscreen.empty()) && o.frames == 0)
        engine::fail("sample_game: --screenshot and --offscreen need --frames N");
    sample_game::run_window(o);
    return 0;
}

// --write-path: the world's own path (or --path's poses) over --frames poses (the profile's default
// 400), written without starting the engine.
int run_write_path(const CommandLine& c) {
    const auto manifest =
        splat_lod::world::read_world_manifest(std::filesystem::path(c.world) / splat_lod::world::kManifestFileName);
    const int frames = c.frames > 0 ? c.frames : 400;
    const auto poses = c.settings.path_file.empty()
                           ? sample_game::sample_world_path(sample_game::WorldGround::of(manifest), frames)
                           : sample_game::read_path_file(c.settings.path_file, frames);
    sample_game::write_path_file(c.write_path, poses);
    std::printf("sample_game: %zu poses of %s's path written to %s\n", poses.size(), c.world.c_str(),
                c.write_path.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"The streamed outdoor walkthrough: a window on the world, or --profile headless"};
    CommandLine c;
    add_options(app, c);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::fprintf(stderr, "sample_game: %s\n", e.what());
        return 1;
    }
    try {
        apply_common(c);
        if (int(c.profile) + int(c.soak) + int(c.reference) > 1)
            engine::fail("sample_game: --profile, --soak and --reference are different runs; give one");
        if (!c.write_path.empty()) return run_write_path(c);
        return c.soak ? run_soak(c) : c.profile ? run_profile(c) : c.reference ? run_reference(c) : run_window(c);
    } catch (const std::exception& e) {
        // The game's own messages already start with "sample_game: "; the engine's name their file.
        const std::string message = e.what();
        std::fprintf(stderr, "%s%s\n", message.rfind("sample_game: ", 0) == 0 ? "" : "sample_game: ", message.c_str());
        return 1;
    }
}
