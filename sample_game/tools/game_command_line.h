#pragma once
// The options that the game (sample_game) and its measurement harness (sample_game_harness) share:
// the world, the image, the LOD rule and the streamer's settings, and how a main reports an error.
#include <array>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine/core/error.h"
#include "sample_game/game_settings.h"

namespace sample_game::cli {

struct GameCommandLine {
    std::string world = "out/world/default";
    int width = 0, height = 0, frames = -1;  // 0 / −1: the program's own default
    double memory_budget_mib = -1.0, upload_budget_mib = -1.0, frame_memory_mib = -1.0;
    std::string mode, upscaler, gpu_storage, transition_placement;
    GameSettings settings;
};

template <typename E, std::size_t N>
E enum_named(const std::array<std::string_view, N>& names, const std::string& text) {
    for (std::size_t i = 0; i < N; ++i)
        if (names[i] == text) return static_cast<E>(i);
    return static_cast<E>(0);  // unreachable: CLI::IsMember checked the name
}

// The LOD rule and raster options (renderer and streamer alike).
inline void add_lod_options(CLI::App& app, GameCommandLine& c) {
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
    app.add_option(
           "--lod-transition-placement", c.transition_placement,
           "Where each fade lies against its switch: auto (default: inside for a bake whose levels "
           "overlap, centred for one whose levels abut, before for any other cloud, the world's chunks included), "
           "before, inside (within the "
           "hard rule's ranges), centred")
        ->check(CLI::IsMember(std::vector<std::string>(plugin_msgs::kTransitionPlacementNames.begin(),
                                                       plugin_msgs::kTransitionPlacementNames.end())));
    app.add_option("--lod-overlap-transition-band", lod.rule.overlap_transition_band,
                   "Placement auto: the band of a bake whose levels overlap at their switches")
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

// The streamer: budgets, retries, load distances, the chunk groups' switch, the GPU's SH degree.
inline void add_streaming_options(CLI::App& app, GameCommandLine& c) {
    app.add_option("--retry-after-frames", c.settings.retry_failed_after_frames,
                   "Try a chunk that failed to load again after N frames (0: never)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--memory-budget-mib", c.memory_budget_mib, "Streamed GPU memory budget (default 384)")
        ->check(CLI::Range(0.01, 1e6));
    app.add_option("--upload-budget-mib", c.upload_budget_mib, "Upload budget per frame (default 8)")
        ->check(CLI::Range(0.01, 1e5));
    app.add_option("--frame-memory-mib", c.frame_memory_mib,
                   "GPU memory the splat pass's per-frame buffers may take; a view that needs more is drawn in "
                   "strips (default 16; 0: no limit)")
        ->check(CLI::Range(0.0, 1e6));
    app.add_flag("--sync-streaming", c.settings.sync_streaming,
                 "Read chunks inside each update (deterministic; tests)");
    app.add_option("--load-distance-scale", c.settings.load_distance_scale,
                   "Load levels this much earlier than the on-axis bound")
        ->capture_default_str();
    app.add_option("--group-cell-px", c.settings.group_cell_px,
                   "Draw a chunk group instead of its chunks where its cell is at most this many pixels (0: never)")
        ->check(CLI::Range(0.0, 1000.0))
        ->capture_default_str();
    app.add_option("--group-grazing-deg", c.settings.group_grazing_deg,
                   "Below this elevation a group's cell counts by its box's foreshortened area (0: by its edge)")
        ->check(CLI::Range(0.0, 90.0))
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
    app.add_option("--gpu-storage", c.gpu_storage, "How the GPU stores Gaussians: compact (default) or full floats")
        ->check(CLI::IsMember({"compact", "full"}));
}

// The world, the image, the field of view, the path, the LOD rule and the streamer. The help texts say
// the program's default size and what --frames counts there.
inline void add_world_options(CLI::App& app, GameCommandLine& c, const std::string& size_defaults,
                              const std::string& frames_help) {
    app.add_option("--world", c.world, "The world's folder (world.json; made by splat_world)")->capture_default_str();
    app.add_option("--width", c.width, "Image width " + size_defaults)->check(CLI::Range(16, 16384));
    app.add_option("--height", c.height, "Image height " + size_defaults)->check(CLI::Range(16, 16384));
    app.add_option("--frames", c.frames, frames_help)->check(CLI::PositiveNumber);
    app.add_option("--fov-y", c.settings.fov_y_deg, "Vertical field of view in degrees")->capture_default_str();
    app.add_option("--path", c.settings.path_file,
                   "Walk this path instead of the world's own: a JSON list of poses (one per frame) or keys "
                   "(sampled over --frames); see sample_game/README.md");
    add_lod_options(app, c);
    add_streaming_options(app, c);
}

// The named choices and budgets in MiB into the settings.
inline void apply(GameCommandLine& c) {
    if (!c.mode.empty())
        c.settings.lod.rule.mode = enum_named<plugin_msgs::LodMode>(plugin_msgs::kLodModeNames, c.mode);
    if (!c.transition_placement.empty())
        c.settings.lod.rule.transition_placement = enum_named<plugin_msgs::TransitionPlacement>(
            plugin_msgs::kTransitionPlacementNames, c.transition_placement);
    if (!c.upscaler.empty())
        c.settings.lod.upscaler = enum_named<plugin_msgs::Upscaler>(plugin_msgs::kUpscalerNames, c.upscaler);
    if (!c.gpu_storage.empty())
        c.settings.gpu_storage = c.gpu_storage == "full" ? splat_lod::GpuStorage::full : splat_lod::GpuStorage::compact;
    if (c.memory_budget_mib > 0.0)
        c.settings.memory_budget_bytes = static_cast<std::uint64_t>(c.memory_budget_mib * static_cast<double>(kMiB));
    if (c.upload_budget_mib > 0.0)
        c.settings.upload_budget_bytes = static_cast<std::uint64_t>(c.upload_budget_mib * static_cast<double>(kMiB));
    if (c.frame_memory_mib >= 0.0)
        c.settings.frame_memory_bytes = static_cast<std::uint64_t>(c.frame_memory_mib * static_cast<double>(kMiB));
}

// Parses the command line and runs `body`; exit code 1 with "<program>: <problem>" on stderr for a bad
// option or any error (the game's own messages already start with "sample_game"; the engine's name
// their file).
template <typename Body>
int run_main(CLI::App& app, int argc, char** argv, const char* program, GameCommandLine& c, Body&& body) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return 1;
    }
    try {
        apply(c);
        return body();
    } catch (const std::exception& e) {
        const std::string message = e.what();
        const bool named = message.rfind("sample_game", 0) == 0;
        std::fprintf(stderr, "%s%s%s\n", named ? "" : program, named ? "" : ": ", message.c_str());
        return 1;
    }
}

}  // namespace sample_game::cli
