#include "engine/ui/overlay.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>

#include "engine/core/error.h"
#include "engine/platform/window.h"
#include "overlay_panels.h"

namespace engine {
namespace {

// ImGui's backends keep one set of process-wide state, so a second overlay would corrupt it.
bool overlay_alive = false;

void place_next_window(ImVec2 position, ImVec2 size) {
    // FirstUseEver: the user may move and resize panels afterwards.
    ImGui::SetNextWindowPos(position, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(size, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
}

bool is_builtin_panel(const std::string& name) {
    return name == UiOverlay::frame_time_panel || name == UiOverlay::scene_panel;
}

}  // namespace

UiOverlay::UiOverlay(Window& window, MessageBus& bus) : scene_tree_(std::make_unique<SceneTreePanel>()) {
    if (overlay_alive) fail("engine::UiOverlay: only one overlay may exist at a time");
    IMGUI_CHECKVERSION();
    context_ = ImGui::CreateContext();
    ImGui::SetCurrentContext(context_);
    // No imgui.ini: tools and tests run from arbitrary folders and must not litter them.
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    if (!ImGui_ImplGlfw_InitForOpenGL(window.native_handle(), true)) {
        ImGui::DestroyContext(context_);
        fail("engine::UiOverlay: ImGui GLFW backend failed to initialise");
    }
    // 4.5 core: the backend then uses its GLSL 410-core shaders.
    if (!ImGui_ImplOpenGL3_Init("#version 450")) {
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext(context_);
        fail("engine::UiOverlay: ImGui OpenGL 3 backend failed to initialise");
    }
    const GlInfo& info = window.info();
    gl_description_ = info.renderer + "\nOpenGL " + info.version + " (" + info.platform + ")";
    statistics_subscription_ =
        bus.subscribe<plugin_msgs::FrameStatistics>([this](const plugin_msgs::FrameStatistics& frame) {
            std::lock_guard lock(history_mutex_);
            history_.push(frame);
        });
    overlay_alive = true;
}

UiOverlay::~UiOverlay() {
    statistics_subscription_.reset();
    ImGui::SetCurrentContext(context_);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext(context_);
    overlay_alive = false;
}

void UiOverlay::set_scene(const Scene* scene) {
    if (scene != scene_) scene_tree_->clear_selection();
    scene_ = scene;
}

void UiOverlay::new_frame() {
    ImGui::SetCurrentContext(context_);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void UiOverlay::render() {
    ImGui::SetCurrentContext(context_);
    // Stacked on the left: the frame-time panel on top, the scene tree filling the rest.
    const float display_height = ImGui::GetIO().DisplaySize.y;
    const float frame_panel_height = std::clamp(0.45f * display_height - 15.0f, 120.0f, 280.0f);
    place_next_window(ImVec2(10, 10), ImVec2(390, frame_panel_height));
    if (ImGui::Begin(frame_time_panel)) {
        std::lock_guard lock(history_mutex_);
        draw_frame_time_panel(history_, gl_description_);
    }
    ImGui::End();
    const float scene_top = frame_panel_height + 20.0f;
    place_next_window(ImVec2(10, scene_top), ImVec2(390, std::max(120.0f, display_height - scene_top - 10.0f)));
    if (ImGui::Begin(scene_panel)) scene_tree_->draw(scene_);
    ImGui::End();
    draw_plugin_panels();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void UiOverlay::draw_plugin_panels() {
    // A copy, so that a panel may add or remove panels (itself included) while drawing.
    const auto panels = panels_;
    const float right = ImGui::GetIO().DisplaySize.x;
    float y = 10.0f;
    for (const auto& [name, draw] : panels) {
        place_next_window(ImVec2(std::max(10.0f, right - 370.0f), y), ImVec2(360, 240));
        y += 30.0f;
        if (ImGui::Begin(name.c_str())) {
            try {
                draw();
            } catch (...) {
                ImGui::End();  // keep ImGui's window stack balanced for the caller's error path
                throw;
            }
        }
        ImGui::End();
    }
}

void UiOverlay::add_panel(const std::string& name, std::function<void()> draw) {
    if (name.empty()) fail("engine::UiOverlay::add_panel(): empty panel name");
    if (!draw) fail("engine::UiOverlay::add_panel(): panel '" + name + "' has no draw function");
    const auto names = panel_names();
    if (is_builtin_panel(name) || std::find(names.begin(), names.end(), name) != names.end())
        fail("engine::UiOverlay::add_panel(): a panel named '" + name + "' already exists");
    panels_.emplace_back(name, std::move(draw));
}

void UiOverlay::remove_panel(const std::string& name) {
    std::erase_if(panels_, [&](const auto& panel) { return panel.first == name; });
}

std::vector<std::string> UiOverlay::panel_names() const {
    std::vector<std::string> names;
    for (const auto& panel : panels_) names.push_back(panel.first);
    return names;
}

bool UiOverlay::wants_mouse() const {
    ImGui::SetCurrentContext(context_);
    return ImGui::GetIO().WantCaptureMouse;
}

bool UiOverlay::wants_keyboard() const {
    ImGui::SetCurrentContext(context_);
    return ImGui::GetIO().WantCaptureKeyboard;
}

FrameHistory UiOverlay::history() const {
    std::lock_guard lock(history_mutex_);
    return history_;
}

}  // namespace engine
