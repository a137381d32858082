// sample_game_harness: the walkthrough's measurements, headless (EGL), over the game's own world code.
//   sample_game_harness --profile [--world DIR] [--out DIR] [--width W --height H] [--frames N]
//               [--memory-budget-mib M] [--upload-budget-mib U] [--frames-png K]
//               [--no-baseline] [--baseline-every K] [--baseline-overview-every K] [--no-preload]
//               [--sync-streaming] [--fog] [--stereo [--ipd M]] [LOD options]
//   sample_game_harness --soak [--world DIR] [--out DIR] [--laps N] [--frames N] [--no-faults] [--retry-after-frames N]
//   sample_game_harness --reference [--world DIR] [--width W --height H] [--frames N] [--fov-y D] [--supersample S]
//   [--force]
// The profile walks the path with LOD and streaming, then the baseline, and writes profile.csv,
// baseline.csv, summary.txt, plots and frames to --out; it prints the summary. Exit code 1 on an
// error (bad option, missing or broken world, no GL); a budget check that fails is a result, printed
// in the summary, not an error. The soak (soak_run.h) walks the path --laps times (--frames poses
// per lap), damaging chunk files of a linked copy of the world on the middle laps, and exits 1 when a
// check fails (a leak, a chunk that does not come back). The reference (reference_run.h) renders the
// profile's reference frames supersampled and caches them beside the world, where the profile with
// the same size, frames and field of view finds them.
#include <cstdio>
#include <memory>
#include <string>

#include "engine/core/error.h"
#include "engine/platform/gl_context.h"
#include "game_command_line.h"
#include "sample_game/harness/profile_run.h"
#include "sample_game/harness/reference_run.h"
#include "sample_game/harness/soak_run.h"

namespace {

struct CommandLine : sample_game::cli::GameCommandLine {
    bool profile = false, soak = false, no_faults = false, reference = false, force = false;
    int supersample = sample_game::kDefaultReferenceSupersample;
    int laps = 10;
    std::string out = "out/game", reference_world;
    int frames_png = 0, baseline_every = 10, baseline_overview_every = 1;
    bool no_baseline = false, no_preload = false;
    bool stereo = false, switch_pops = false;
    float ipd = 0.063f;
};

// What to run headless: the profile, the soak or the reference, and their own settings.
void add_run_options(CLI::App& app, CommandLine& c) {
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
    app.add_option("--reference-world", c.reference_world,
                   "Profile: score against this world's cached reference instead of --world's (the same world "
                   "stored another way, e.g. splat_world --chunk-codec ply, to measure what the storage costs)");
    app.add_option("--laps", c.laps, "Soak: laps of the path (default 10)")->check(CLI::Range(2, 100000));
    app.add_flag("--no-faults", c.no_faults, "Soak: leave the chunk files alone (stream the world itself)");
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
    app.add_flag("--fog", c.settings.fog.enabled,
                 "Draw the windowed game's distance fog too (its GPU time is the CSV's gpu_fog_ms)");
    app.add_flag("--stereo", c.stereo,
                 "Profile: draw each LOD frame again as a stereo pair and compare its cost (CSV stereo_frame_ms, "
                 "stereo_eye_psnr; the summary's settings line)");
    app.add_flag("--switch-pops", c.switch_pops,
                 "Profile: draw each LOD frame after the first again with the frame before's selection (CSV "
                 "switch_pop; its peak and mean on the summary's settings line)");
    app.add_option("--ipd", c.ipd, "With --stereo: the distance between the eyes (m)")
        ->check(CLI::Range(0.0f, 10.0f))
        ->capture_default_str();
}

void add_options(CLI::App& app, CommandLine& c) {
    add_run_options(app, c);
    add_profile_options(app, c);
    sample_game::cli::add_world_options(app, c, "(default 640×360; soak 320×180)",
                                        "Poses along the path (default 400); soak: per lap (default 200)");
    app.add_option("--out", c.out, "Profile output folder (the soak's default is out/soak)")->capture_default_str();
}

// After the options are checked: the GL context every run draws in, and which renderer it is.
std::unique_ptr<engine::HeadlessGlContext> headless_context() {
    auto context = engine::HeadlessGlContext::create();
    std::fprintf(stderr, "sample_game_harness: %s on %s\n", context->info().renderer.c_str(),
                 context->info().platform.c_str());
    return context;
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
    o.stereo_ipd = c.stereo ? c.ipd : 0.0f;
    o.switch_pops = c.switch_pops;
    o.reference_supersample = c.supersample;
    o.reference_world = c.reference_world;
    sample_game::validate(o);  // before making a GL context: option errors come first
    const auto context = headless_context();
    const sample_game::ProfileOutcome outcome = sample_game::run_profile(o, stderr);
    std::printf("%s", outcome.summary_text.c_str());
    if (!outcome.plot_problem.empty()) std::fprintf(stderr, "sample_game_harness: %s\n", outcome.plot_problem.c_str());
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
    const auto context = headless_context();
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
    const auto context = headless_context();
    const sample_game::SoakOutcome outcome = sample_game::run_soak(o, stderr);
    std::printf("%s", outcome.summary_text.c_str());
    return outcome.passed ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"The walkthrough's measurements, headless: --profile, --soak or --reference"};
    CommandLine c;
    add_options(app, c);
    return sample_game::cli::run_main(app, argc, argv, "sample_game_harness", c, [&] {
        if (int(c.profile) + int(c.soak) + int(c.reference) != 1)
            engine::fail("sample_game_harness: give one of --profile, --soak and --reference");
        return c.soak ? run_soak(c) : c.profile ? run_profile(c) : run_reference(c);
    });
}
