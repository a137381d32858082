#pragma once
// A GLFW window with an OpenGL 4.5 core context, current on the creating thread. The context
// comes from GLFW's EGL context API (the same driver path as the headless context), falling
// back to the native one (GLX) when the EGL window cannot be made. Keyboard and mouse state is
// polled once per poll_events() so that a frame sees one consistent snapshot.
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "engine/platform/gl_context.h"

struct GLFWwindow;

namespace engine {

// The keys the engine's tools use; kept small so that GLFW stays out of public headers.
enum class Key { w, a, s, d, q, e, left_shift, escape, f1, space };
enum class MouseButton { left, right, middle };

class Window {
public:
    // Opens the window and makes its context current. Throws engine::Error when there is no
    // display or the driver lacks OpenGL 4.3 compute (naming what was found).
    static std::unique_ptr<Window> create(const std::string& title, int width, int height, bool vsync);
    ~Window();  // the last window alive also terminates GLFW
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    bool should_close() const;
    void request_close();
    // Processes window-system events and takes the input snapshot for this frame.
    void poll_events();
    void swap_buffers();
    glm::ivec2 framebuffer_size() const;  // in pixels; (0, 0) while minimised

    const GlInfo& info() const { return info_; }
    GLFWwindow* native_handle() const { return window_; }  // for the ImGui GLFW backend

    bool key_down(Key key) const;
    bool mouse_down(MouseButton button) const;
    glm::vec2 mouse_position() const { return mouse_position_; }  // window coordinates, top-left origin
    // The cursor in framebuffer pixels (top-left origin): the window coordinates scaled by the
    // framebuffer's size over the window's, which differ on high-density displays.
    glm::vec2 cursor_pixel() const;
    glm::vec2 mouse_delta() const { return mouse_delta_; }  // since the previous poll_events()
    float scroll_delta() const { return scroll_delta_; }    // wheel steps since the previous poll

private:
    Window() = default;
    static void scroll_callback(GLFWwindow* window, double x, double y);

    GLFWwindow* window_ = nullptr;
    GlInfo info_;
    glm::vec2 mouse_position_{0.0f};
    glm::vec2 mouse_delta_{0.0f};
    bool have_mouse_position_ = false;
    float scroll_accumulated_ = 0.0f;
    float scroll_delta_ = 0.0f;
};

}  // namespace engine
