#pragma once
// The windowed game (`sample_game`): a GLFW window on the streamed world with
// the engine's ImGui overlay (frame time, scene tree, the splat plugin's "Splat LOD" panel) and
// the game's "Streaming" and "Walkthrough" panels. The camera follows the walkthrough path,
// looping, until the user flies it: W/A/S/D move, E/Q up/down, Shift faster, right mouse button +
// drag turns, the wheel scales the speed (as engine_view). Space plays/pauses the path, the
// "follow path" checkbox puts the camera back on it, F1 toggles the overlay, Escape quits.
// Edits in the LOD panel reach the streamer too (one LodSettings for both; game_settings.h).
#include <filesystem>

#include "sample_game/game_settings.h"

namespace sample_game {

struct WindowOptions {
    std::filesystem::path world;
    int width = 1280, height = 720;
    GameSettings settings;
    int path_frames = 1800;            // poses of the looping path (30 s at 60 frames per second)
    int frames = 0;                    // 0: until the window closes; else quit after this many (tests)
    std::filesystem::path screenshot;  // after the last frame: the window, overlay included
    std::filesystem::path offscreen;   // after the last frame: the rendered frame without overlay
    bool no_ui = false;
    // > 0: a stereo pair this far apart (metres), side by side, each eye half the window wide
    // (engine::stereo_eyes: one selection, the centre's; streaming follows the centre).
    float stereo_ipd = 0.0f;
};

// Throws engine::Error on a missing display, a bad world or option (naming it).
void run_window(const WindowOptions& options);

}  // namespace sample_game
