#pragma once
// The Dear ImGui overlay of windowed mode: a frame-time panel fed by the FrameStatistics the
// renderer publishes, a scene tree panel, and panels that plugins add by name. It draws into
// whatever framebuffer is bound when render() runs (the window's default one in the viewer).
//
// Frame protocol: new_frame(); any ImGui calls of the application; render().
// One overlay at a time: ImGui's GLFW and OpenGL backends keep process-wide state.
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/message_bus.h"
#include "engine/ui/frame_history.h"

struct ImGuiContext;

namespace engine {

class Window;
class Scene;
class SceneTreePanel;

class UiOverlay {
public:
    // Needs the window's context current. Subscribes to FrameStatistics on `bus`.
    UiOverlay(Window& window, MessageBus& bus);
    ~UiOverlay();
    UiOverlay(const UiOverlay&) = delete;
    UiOverlay& operator=(const UiOverlay&) = delete;

    // The scene the tree panel shows; nullptr for none. Must outlive its use by render().
    void set_scene(const Scene* scene);

    void new_frame();
    // Builds the built-in and plugin panels, then draws them into the bound framebuffer.
    void render();

    // A plugin panel: `draw` fills the body of an ImGui window titled `name` each frame.
    // Throws engine::Error when the name is taken (the built-in panels' names included).
    void add_panel(const std::string& name, std::function<void()> draw);
    void remove_panel(const std::string& name);  // no effect for an unknown name
    std::vector<std::string> panel_names() const;

    // True when ImGui is using the mouse or keyboard (a panel is hovered or a field has focus):
    // the camera should then ignore that input.
    bool wants_mouse() const;
    bool wants_keyboard() const;

    // For code built with its own copy of Dear ImGui (a plugin linked against libimgui.a):
    // call ImGui::SetCurrentContext(overlay.imgui_context()) before drawing.
    ImGuiContext* imgui_context() const { return context_; }

    FrameHistory history() const;  // a copy, taken under the lock the bus handler uses

    static constexpr const char* frame_time_panel = "Frame time";
    static constexpr const char* scene_panel = "Scene";

private:
    void draw_plugin_panels();

    ImGuiContext* context_ = nullptr;
    std::string gl_description_;
    mutable std::mutex history_mutex_;  // the bus may deliver from another thread
    FrameHistory history_;
    Subscription statistics_subscription_;
    std::unique_ptr<SceneTreePanel> scene_tree_;
    const Scene* scene_ = nullptr;
    std::vector<std::pair<std::string, std::function<void()>>> panels_;
};

}  // namespace engine
