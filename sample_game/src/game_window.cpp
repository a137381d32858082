#include "sample_game/game_window.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "engine/core/error.h"
#include "engine/engine.h"
#include "engine/platform/window.h"
#include "engine/render/image.h"
#include "engine/render/render_target.h"
#include "engine/ui/fly_camera.h"
#include "engine/ui/fly_camera_input.h"
#include "engine/ui/overlay.h"
#include "sample_game/game_world.h"
#include "sample_game/streaming_panel.h"
#include "sample_game/world_path.h"
#include "splat_lod/splat_lod_plugin.h"

namespace sample_game {
namespace {

constexpr float kPathPosesPerSecond = 60.0f;  // the path's playback rate at speed 1

// Moves and sizes the current ImGui window the first time it is drawn (the overlay has already
// placed it with its own cascade, so ImGuiCond_FirstUseEver would no longer apply); after that the
// user may move it.
void place_once(bool& placed, const ImVec2& position, const ImVec2& size) {
    if (placed) return;
    ImGui::SetWindowPos(position, ImGuiCond_Always);
    ImGui::SetWindowSize(size, ImGuiCond_Always);
    placed = true;
}

bool moves_camera(const engine::FlyCameraInput& in) {
    return in.forward || in.back || in.left || in.right || in.up || in.down ||
           (in.look && (in.mouse_delta.x != 0.0f || in.mouse_delta.y != 0.0f));
}

class Game {
public:
    explicit Game(const WindowOptions& options);
    ~Game();
    void run();

private:
    void add_panels();
    void update_camera(float seconds);
    bool draw_frame(bool last, double frame_ms);
    void draw_walkthrough_panel();

    const WindowOptions& options_;
    // Declared first so it is destroyed last: everything below frees GL objects in its context.
    std::unique_ptr<engine::Window> window_;
    engine::Engine engine_;
    std::unique_ptr<GameWorld> world_;
    std::unique_ptr<engine::UiOverlay> overlay_;
    std::unique_ptr<engine::RenderTarget> target_, right_target_;  // the right eye's in stereo
    std::shared_ptr<StreamingPanel> streaming_;
    engine::Subscription lod_subscription_;
    std::vector<PathPose> path_;
    engine::FlyCamera fly_;
    float path_position_ = 0.0f;         // index into path_, fractional
    std::optional<glm::vec3> last_eye_;  // the camera of the last streamer update; none after a jump
    float path_speed_ = 1.0f;
    bool follow_ = true, playing_ = true;
    bool show_ui_;
    bool f1_was_down_ = false, space_was_down_ = false;
    bool streaming_placed_ = false, walkthrough_placed_ = false;
    std::uint64_t frame_ = 0;
};

Game::Game(const WindowOptions& options) : options_(options), show_ui_(!options.no_ui) {
    validate(options.settings);
    if (options.path_frames < 10) engine::fail("sample_game: --path-frames must be at least 10");
    require_world_folder(options.world);
    // A fixed frame count is a test run: waiting for vertical blank only slows it.
    window_ = engine::Window::create("sample_game: " + options.world.string(), options.width, options.height,
                                     options.frames == 0);
    engine_.plugins().add_static(splat_lod::make_plugin());
    world_ = std::make_unique<GameWorld>(engine_, options.world, options.settings);
    path_ = world_->path(options.path_frames);
    fly_.look_at(path_.front().eye, path_.front().eye + path_.front().forward);
    fly_.speed = 10.0f;
    overlay_ = std::make_unique<engine::UiOverlay>(*window_, engine_.bus());
    overlay_->set_scene(&world_->scene());
    add_panels();
    // The LOD panel edits the one LodSettings: the splat pass takes it from the bus, the streamer here.
    lod_subscription_ = engine_.bus().subscribe<plugin_msgs::LodSettings>([this](const plugin_msgs::LodSettings& lod) {
        GameSettings s = world_->settings();
        s.lod = lod;
        world_->set_settings(s);
    });
    world_->publish_lod_settings();  // the panels were made after the world first published them
}

Game::~Game() {
    lod_subscription_.reset();
    overlay_.reset();
    world_.reset();
}

void Game::add_panels() {
    for (const std::string& name : engine_.plugins().names())
        engine_.plugins().find(name)->add_ui_panels(*overlay_, engine_.bus());
    streaming_ = std::make_shared<StreamingPanel>(engine_.bus());
    ImGuiContext* context = overlay_->imgui_context();
    // This library links its own copy of Dear ImGui (as the splat plugin does): draw into the overlay's context.
    // The overlay cascades plugin panels at the top right; the game's own go below the LOD panel
    // and at the bottom left, so that all of them can be read at once at 1280x720.
    overlay_->add_panel(StreamingPanel::title, [this, context] {
        ImGui::SetCurrentContext(context);
        place_once(streaming_placed_, ImVec2(std::max(10.0f, ImGui::GetIO().DisplaySize.x - 430.0f), 290.0f),
                   ImVec2(420.0f, 300.0f));
        GameSettings s = world_->settings();
        int memory_mib = static_cast<int>(s.memory_budget_bytes / kMiB);
        float upload_mib = static_cast<float>(static_cast<double>(s.upload_budget_bytes) / static_cast<double>(kMiB));
        if (streaming_->draw(memory_mib, upload_mib)) {
            s.memory_budget_bytes = static_cast<std::uint64_t>(memory_mib) * kMiB;
            s.upload_budget_bytes =
                static_cast<std::uint64_t>(static_cast<double>(upload_mib) * static_cast<double>(kMiB));
            world_->set_settings(s);
        }
    });
    overlay_->add_panel("Walkthrough", [this, context] {
        ImGui::SetCurrentContext(context);
        place_once(walkthrough_placed_, ImVec2(420.0f, std::max(10.0f, ImGui::GetIO().DisplaySize.y - 190.0f)),
                   ImVec2(420.0f, 180.0f));
        draw_walkthrough_panel();
    });
}

void Game::draw_walkthrough_panel() {
    ImGui::Checkbox("follow path", &follow_);
    ImGui::SameLine();
    ImGui::Checkbox("playing (Space)", &playing_);
    const int count = static_cast<int>(path_.size());
    int index = std::clamp(static_cast<int>(path_position_), 0, count - 1);
    if (ImGui::SliderInt("position", &index, 0, count - 1)) {
        path_position_ = static_cast<float>(index);
        follow_ = true;
        last_eye_.reset();  // a jump: nothing for the streamer to anticipate
    }
    ImGui::SliderFloat("speed", &path_speed_, 0.1f, 8.0f, "%.1fx");
    const PathPose& pose = path_[static_cast<std::size_t>(index)];
    const glm::vec3 eye = fly_.position();
    ImGui::Text("segment %s, t %.3f", std::string(to_string(pose.segment)).c_str(), static_cast<double>(pose.t));
    ImGui::Text("camera %.1f, %.1f, %.1f  (%.1f m above ground)", static_cast<double>(eye.x),
                static_cast<double>(eye.y), static_cast<double>(eye.z),
                static_cast<double>(eye.y - world_->ground().height(eye.x, eye.z)));
    ImGui::TextUnformatted("WASD/QE + right mouse: fly (leaves the path)");
}

void Game::update_camera(float seconds) {
    const bool f1 = window_->key_down(engine::Key::f1), space = window_->key_down(engine::Key::space);
    if (f1 && !f1_was_down_) show_ui_ = !show_ui_;
    if (space && !space_was_down_) playing_ = !playing_;
    f1_was_down_ = f1;
    space_was_down_ = space;
    if (window_->key_down(engine::Key::escape)) window_->request_close();
    const engine::FlyCameraInput input = engine::read_fly_camera_input(*window_, show_ui_ && overlay_->wants_mouse(),
                                                                       show_ui_ && overlay_->wants_keyboard());
    if (moves_camera(input)) follow_ = false;  // the user flies: leave the path where it was
    if (follow_) {
        if (playing_) {
            // Scripted runs (--frames) step one pose per frame so that they are repeatable.
            const float step = options_.frames > 0 ? 1.0f : seconds * kPathPosesPerSecond * path_speed_;
            const float next = path_position_ + step;
            if (next >= static_cast<float>(path_.size())) last_eye_.reset();  // back to the start
            path_position_ = std::fmod(next, static_cast<float>(path_.size()));
        }
        const PathPose& pose = path_[static_cast<std::size_t>(path_position_)];
        fly_.look_at(pose.eye, pose.eye + pose.forward);
    } else {
        fly_.update(input, seconds);
    }
}

bool Game::draw_frame(bool last, double frame_ms) {
    const glm::ivec2 size = window_->framebuffer_size();
    const bool stereo = options_.stereo_ipd > 0.0f;
    if (size.x <= 0 || size.y <= 0 || (stereo && size.x < 2)) return false;
    const glm::ivec2 eye_size(stereo ? size.x / 2 : size.x, size.y);
    if (!target_ || target_->width() != eye_size.x || target_->height() != eye_size.y) {
        target_ = std::make_unique<engine::RenderTarget>(eye_size.x, eye_size.y);
        if (stereo) right_target_ = std::make_unique<engine::RenderTarget>(eye_size.x, eye_size.y);
    }
    const engine::CameraView camera = world_->camera(fly_.position(), fly_.forward(), eye_size.x, eye_size.y);
    world_->update_streaming(camera, frame_++, last_eye_ ? camera.position - *last_eye_ : glm::vec3(0.0f));
    last_eye_ = camera.position;
    if (stereo) {
        const engine::StereoEyes eyes = engine::stereo_eyes(camera, options_.stereo_ipd);
        engine_.renderer().render(world_->scene(), eyes.left, *target_);
        engine_.renderer().render(world_->scene(), eyes.right, *right_target_);
    } else {
        engine_.renderer().render(world_->scene(), camera, *target_);
    }
    auto& streamer = world_->streamer();
    const plugin_msgs::ResidencyReport& residency = streamer.residency();
    streaming_->record({world_->census(), streamer.chunk_count(), streamer.resident_bytes(),
                        streamer.settings().memory_budget_bytes, streamer.stats().uploaded_bytes_last_update,
                        streamer.settings().upload_budget_bytes_per_frame, frame_ms, residency.drawn_chunks,
                        residency.drawn_groups, residency.groups.resident, streamer.group_count()});
    if (stereo) {
        engine::present_to_window(*target_, size, {0, 0}, eye_size);
        engine::present_to_window(*right_target_, size, {eye_size.x, 0}, eye_size);
    } else {
        engine::present_to_window(*target_, size);
    }
    if (show_ui_) {
        overlay_->new_frame();
        overlay_->render();
    }
    if (last) {
        if (!options_.screenshot.empty()) engine::write_png(options_.screenshot, engine::read_window(size));
        if (!options_.offscreen.empty())
            engine::write_png(options_.offscreen,
                              stereo ? engine::side_by_side(target_->read_color(), right_target_->read_color())
                                     : target_->read_color());
    }
    window_->swap_buffers();
    return true;
}

void Game::run() {
    using Clock = std::chrono::steady_clock;
    auto previous = Clock::now();
    double last_frame_ms = 0.0;
    int drawn = 0;
    while (!window_->should_close() && (options_.frames == 0 || drawn < options_.frames)) {
        window_->poll_events();
        const auto now = Clock::now();
        // Clamped so that a stall (window drag, a slow frame) does not fling the camera away.
        const float seconds = std::min(std::chrono::duration<float>(now - previous).count(), 0.1f);
        last_frame_ms = std::chrono::duration<double, std::milli>(now - previous).count();
        previous = now;
        update_camera(seconds);
        if (draw_frame(options_.frames > 0 && drawn + 1 == options_.frames, last_frame_ms)) ++drawn;
    }
    if (options_.frames > 0 && drawn < options_.frames && !options_.screenshot.empty())
        engine::fail("sample_game: the window closed after " + std::to_string(drawn) + " of " +
                     std::to_string(options_.frames) + " frames; no screenshot written");
}

}  // namespace

void run_window(const WindowOptions& options) {
    Game game(options);
    game.run();
}

}  // namespace sample_game
