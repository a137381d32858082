// sample_game: the streamed outdoor walkthrough (sample_game/README.md), in a window.
//   sample_game [--world DIR] [--width W --height H] [--frames N] [--screenshot PNG] [--stereo [--ipd M]]
//               [LOD and streaming options]
//   sample_game --write-path FILE [--world DIR] [--frames N] [--path FILE]
// The window flies freely or follows the world's path, with the LOD and streaming panels. The
// measurements of the walkthrough (profile, soak, reference) are sample_game_harness's; this program
// links neither the evaluation nor the world generator. Exit code 1 on an error (bad option, missing or
// broken world, no display).
#include <cstdio>
#include <string>

#include "engine/core/error.h"
#include "game_command_line.h"
#include "sample_game/game_window.h"
#include "sample_game/path_file.h"
#include "sample_game/world_path.h"

namespace {

struct CommandLine : sample_game::cli::GameCommandLine {
    int path_frames = 1800;
    bool no_ui = false, no_fog = false;
    bool stereo = false;
    float ipd = 0.063f;
    std::string screenshot, offscreen, write_path;
};

void add_options(CLI::App& app, CommandLine& c) {
    sample_game::cli::add_world_options(app, c, "(default 1280×720)",
                                        "Quit after N frames (--write-path: poses written, default 400)");
    app.add_option("--write-path", c.write_path,
                   "Write the world's path over --frames poses (or --path's) as a poses file and exit");
    app.add_option("--path-frames", c.path_frames, "Poses of the looping path")
        ->check(CLI::Range(10, 1000000))
        ->capture_default_str();
    app.add_option("--screenshot", c.screenshot, "After the last --frames frame, write the window as PNG");
    app.add_option("--offscreen", c.offscreen, "Also write the frame without overlay as PNG");
    app.add_flag("--no-ui", c.no_ui, "Start with the overlay hidden (F1 toggles it)");
    app.add_flag("--stereo", c.stereo, "Draw the left and right eyes side by side, each half the window wide");
    app.add_option("--ipd", c.ipd, "With --stereo: the distance between the eyes (m)")
        ->check(CLI::Range(0.0f, 10.0f))
        ->capture_default_str();
    app.add_flag("--no-fog", c.no_fog, "No distance fog (on by default: meshes and splats by the frame's depth)");
    app.add_option("--fog-density", c.settings.fog.density, "Distance fog per metre (half fog at ln 2 / density)")
        ->check(CLI::Range(0.0, 10.0))
        ->capture_default_str();
}

int run_window(const CommandLine& c) {
    sample_game::WindowOptions o;
    o.world = c.world;
    o.width = c.width > 0 ? c.width : 1280;
    o.height = c.height > 0 ? c.height : 720;
    o.settings = c.settings;
    o.settings.fog.enabled = !c.no_fog;
    o.path_frames = c.path_frames;
    o.frames = c.frames > 0 ? c.frames : 0;
    o.screenshot = c.screenshot;
    o.offscreen = c.offscreen;
    o.no_ui = c.no_ui;
    o.stereo_ipd = c.stereo ? c.ipd : 0.0f;
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
    CLI::App app{"The streamed outdoor walkthrough in a window (sample_game_harness measures it headless)"};
    CommandLine c;
    add_options(app, c);
    return sample_game::cli::run_main(app, argc, argv, "sample_game", c,
                                      [&] { return c.write_path.empty() ? run_window(c) : run_write_path(c); });
}
