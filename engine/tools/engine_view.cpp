// engine_view: opens a window on a scene file, with a fly camera and the ImGui overlay.
//   engine_view --scene FILE [--width W --height H] [--frames N --screenshot OUT.png] [--no-ui]
//               [--stereo [--ipd M]]
// Each frame renders offscreen through Engine::renderer() (the same path as the headless tools
// and tests), blits that frame to the window and draws the overlay on top.
// Controls: W/A/S/D move, E/Q up/down, Shift faster, right mouse button + drag turns, the
// wheel scales the speed, a left click picks what is under the cursor (its node, component and world
// point in the "Pick" panel, a cross on screen), F1 toggles the overlay, Escape quits.
// --stereo: the left and right eyes (engine::stereo_eyes, --ipd apart, one selection) side by side, each
// half the window wide with the window's vertical field of view; picking is off.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "engine/assets/mesh_asset.h"
#include "engine/core/error.h"
#include "engine/engine.h"
#include "engine/platform/window.h"
#include "engine/plugin/static_plugins.h"
#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "engine/render/render_target.h"
#include "engine/render/scene_camera.h"
#include "engine/scene/builtin_components.h"
#include "engine/ui/fly_camera.h"
#include "engine/ui/fly_camera_input.h"
#include "engine/ui/overlay.h"
#include "engine/ui/pick_tool.h"

namespace {

struct Options {
    std::filesystem::path scene;
    int width = 1280;
    int height = 720;
    int frames = 0;  // 0: until the window closes
    std::filesystem::path screenshot;
    std::filesystem::path offscreen;
    bool no_ui = false;
    bool stereo = false;
    float ipd = 0.063f;
};

// Where the view starts and the lens it keeps; scene_size scales the fly speed.
struct ViewSetup {
    glm::mat4 camera_to_world{1.0f};
    float fov_y = glm::radians(50.0f);
    float znear = 0.1f;
    float zfar = 1000.0f;
    float scene_size = 1.0f;
};

// The scene's first camera, or a view that frames its bounds (render/scene_camera.h).
ViewSetup initial_view(const engine::Scene& scene, int width, int height) {
    const engine::CameraView camera = engine::scene_camera(scene, "", width, height)
                                          .value_or(engine::framing_camera(scene, width, height, glm::radians(50.0f)));
    ViewSetup view;
    view.camera_to_world = glm::inverse(camera.view);
    view.fov_y = camera.fov_y;
    view.znear = camera.znear;
    view.zfar = camera.zfar;
    if (const auto bounds = scene.world_bounds())
        view.scene_size = std::max(glm::length(bounds->max - bounds->min), 1e-2f);
    return view;
}

// The scene's own camera matrix is used exactly (roll included) until the user first moves.
struct ViewerCamera {
    explicit ViewerCamera(const ViewSetup& setup) : view(setup), fly(setup.camera_to_world) {
        fly.speed = 0.5f * setup.scene_size;
    }
    glm::mat4 camera_to_world() const { return moved ? fly.camera_to_world() : view.camera_to_world; }

    ViewSetup view;
    engine::FlyCamera fly;
    bool moved = false;
};

bool changes_view(const engine::FlyCameraInput& in) {
    return in.forward || in.back || in.left || in.right || in.up || in.down ||
           (in.look && (in.mouse_delta.x != 0.0f || in.mouse_delta.y != 0.0f));
}

class Viewer {
public:
    explicit Viewer(const Options& options);
    void run();

private:
    bool draw_frame(bool last);
    void update_camera(float seconds);
    void write_screenshots();

    const Options& options_;
    // Declared first so it is destroyed last: everything below frees GL objects in its context.
    std::unique_ptr<engine::Window> window_;
    engine::Engine engine_;
    std::unique_ptr<engine::Scene> scene_;
    std::unique_ptr<engine::UiOverlay> overlay_;
    std::unique_ptr<engine::PickTool> pick_;
    std::unique_ptr<engine::RenderTarget> target_, right_target_;  // the right eye's with --stereo
    std::optional<ViewerCamera> camera_;
    bool show_ui_;
    bool f1_was_down_ = false;
};

Viewer::Viewer(const Options& options) : options_(options), show_ui_(!options.no_ui) {
    // A fixed frame count is a test or benchmark run: waiting for vertical blank only slows it.
    window_ = engine::Window::create("engine_view: " + options.scene.filename().string(), options.width, options.height,
                                     options.frames == 0);
    engine_add_static_plugins(engine_.plugins());
    scene_ = engine_.load_scene(options.scene);
    camera_.emplace(initial_view(*scene_, options.width, options.height));
    overlay_ = std::make_unique<engine::UiOverlay>(*window_, engine_.bus());
    overlay_->set_scene(scene_.get());
    pick_ = std::make_unique<engine::PickTool>(engine_.renderer(), *overlay_);
    for (const std::string& name : engine_.plugins().names())
        engine_.plugins().find(name)->add_ui_panels(*overlay_, engine_.bus());
}

void Viewer::update_camera(float seconds) {
    const bool f1 = window_->key_down(engine::Key::f1);
    if (f1 && !f1_was_down_) show_ui_ = !show_ui_;
    f1_was_down_ = f1;
    if (window_->key_down(engine::Key::escape)) window_->request_close();
    const engine::FlyCameraInput input = engine::read_fly_camera_input(*window_, show_ui_ && overlay_->wants_mouse(),
                                                                       show_ui_ && overlay_->wants_keyboard());
    camera_->fly.update(input, seconds);
    if (!options_.stereo) pick_->update(*window_, show_ui_ && overlay_->wants_mouse());
    camera_->moved = camera_->moved || changes_view(input);
}

// Returns false when there was nothing to draw into (a minimised window).
bool Viewer::draw_frame(bool last) {
    const glm::ivec2 size = window_->framebuffer_size();
    if (size.x <= 0 || size.y <= 0 || (options_.stereo && size.x < 2)) return false;
    const glm::ivec2 eye_size(options_.stereo ? size.x / 2 : size.x, size.y);
    if (!target_ || target_->width() != eye_size.x || target_->height() != eye_size.y) {
        target_ = std::make_unique<engine::RenderTarget>(eye_size.x, eye_size.y);
        if (options_.stereo) right_target_ = std::make_unique<engine::RenderTarget>(eye_size.x, eye_size.y);
    }
    const ViewSetup& lens = camera_->view;
    const engine::CameraView view =
        engine::make_camera(camera_->camera_to_world(), lens.fov_y, eye_size.x, eye_size.y, lens.znear, lens.zfar);
    if (options_.stereo) {
        const engine::StereoEyes eyes = engine::stereo_eyes(view, options_.ipd);
        engine_.renderer().render(*scene_, eyes.left, *target_);
        engine_.renderer().render(*scene_, eyes.right, *right_target_);
        engine::present_to_window(*target_, size, {0, 0}, eye_size);
        engine::present_to_window(*right_target_, size, {eye_size.x, 0}, eye_size);
    } else {
        engine_.renderer().render(*scene_, view, *target_);
        pick_->after_frame(view);
        engine::present_to_window(*target_, size);
    }
    if (show_ui_) {
        overlay_->new_frame();
        overlay_->render();
    }
    if (last) write_screenshots();
    window_->swap_buffers();
    return true;
}

void Viewer::write_screenshots() {
    if (!options_.screenshot.empty())
        engine::write_png(options_.screenshot, engine::read_window(window_->framebuffer_size()));
    if (options_.offscreen.empty()) return;
    engine::write_png(options_.offscreen, options_.stereo
                                              ? engine::side_by_side(target_->read_color(), right_target_->read_color())
                                              : target_->read_color());
}

void Viewer::run() {
    using clock = std::chrono::steady_clock;
    auto previous = clock::now();
    int drawn = 0;
    while (!window_->should_close() && (options_.frames == 0 || drawn < options_.frames)) {
        window_->poll_events();
        const auto now = clock::now();
        // Clamped so that a stall (window drag, breakpoint) does not fling the camera away.
        const float seconds = std::min(std::chrono::duration<float>(now - previous).count(), 0.1f);
        previous = now;
        update_camera(seconds);
        if (draw_frame(options_.frames > 0 && drawn + 1 == options_.frames)) ++drawn;
    }
    if (options_.frames > 0 && drawn < options_.frames && !options_.screenshot.empty())
        engine::fail("the window closed after " + std::to_string(drawn) + " of " + std::to_string(options_.frames) +
                     " frames; no screenshot written");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Opens a window on a scene with a fly camera and the engine's overlay."};
    Options options;
    // No ExistingFile check: the scene loader's message names the file in the tool's own format.
    app.add_option("--scene", options.scene, "Scene file (JSON)")->required();
    app.add_option("--width", options.width, "Window width in pixels")->check(CLI::Range(16, 16384));
    app.add_option("--height", options.height, "Window height in pixels")->check(CLI::Range(16, 16384));
    auto* frames =
        app.add_option("--frames", options.frames, "Quit after this many frames")->check(CLI::PositiveNumber);
    app.add_option("--screenshot", options.screenshot,
                   "After the last frame, write the window (overlay included) as PNG")
        ->needs(frames);
    app.add_option("--offscreen", options.offscreen,
                   "After the last frame, also write the offscreen frame without overlay as PNG (checks the blit)")
        ->needs(frames);
    app.add_flag("--no-ui", options.no_ui, "Start with the overlay hidden (F1 toggles it)");
    app.add_flag("--stereo", options.stereo, "Draw the left and right eyes side by side");
    app.add_option("--ipd", options.ipd, "With --stereo: the distance between the eyes, in the scene's units")
        ->check(CLI::Range(0.0f, 1e6f));
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::fprintf(stderr, "engine_view: %s\n", e.what());
        return 1;
    }
    try {
        Viewer viewer(options);
        viewer.run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "engine_view: %s\n", e.what());
        return 1;
    }
    return 0;
}
