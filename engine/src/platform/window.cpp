#include "engine/platform/window.h"

// GLFW must not pull in a GL header of its own: epoxy provides the GL API.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <mutex>
#include <string>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/gl/gl.h"

namespace engine {
namespace {

// GLFW reports errors through one process-wide callback; keep the latest for our messages.
std::mutex glfw_error_mutex;
std::string glfw_last_error;

void record_glfw_error(int code, const char* description) {
    std::lock_guard lock(glfw_error_mutex);
    glfw_last_error = std::string(description ? description : "?") + " (GLFW error " + std::to_string(code) + ")";
}

std::string take_glfw_error() {
    std::lock_guard lock(glfw_error_mutex);
    std::string message = glfw_last_error.empty() ? "no GLFW error reported" : glfw_last_error;
    glfw_last_error.clear();
    return message;
}

// glfwInit/glfwTerminate are process-wide, so they follow the number of live windows.
int live_windows = 0;

void acquire_glfw() {
    if (live_windows == 0) {
        glfwSetErrorCallback(record_glfw_error);
        if (glfwInit() != GLFW_TRUE)
            fail("engine::Window: no display (set DISPLAY or use headless mode): " + take_glfw_error());
    }
    ++live_windows;
}

void release_glfw() {
    if (--live_windows == 0) glfwTerminate();
}

struct ContextRequest {
    int creation_api;  // GLFW_EGL_CONTEXT_API or GLFW_NATIVE_CONTEXT_API
    int major;         // 0: whatever the driver gives (used only to report what was found)
    int minor;
    const char* platform;
};

GLFWwindow* open_window(const ContextRequest& request, const std::string& title, int width, int height) {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, request.creation_api);
    if (request.major > 0) {
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, request.major);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, request.minor);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    }
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, gl_debug_requested() ? GLFW_TRUE : GLFW_FALSE);
    return glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
}

// Asks for 4.5 then 4.3, each through EGL first and the native API second; records why each
// attempt failed so that the final error can say it.
GLFWwindow* open_gl45_window(const std::string& title, int width, int height, std::string& platform,
                             std::string& tried) {
    const ContextRequest requests[] = {{GLFW_EGL_CONTEXT_API, 4, 5, "glfw-egl"},
                                       {GLFW_NATIVE_CONTEXT_API, 4, 5, "glfw-glx"},
                                       {GLFW_EGL_CONTEXT_API, 4, 3, "glfw-egl"},
                                       {GLFW_NATIVE_CONTEXT_API, 4, 3, "glfw-glx"}};
    for (const ContextRequest& request : requests) {
        if (GLFWwindow* window = open_window(request, title, width, height)) {
            platform = request.platform;
            return window;
        }
        const std::string why = take_glfw_error();
        tried += std::string(" ") + request.platform + " " + std::to_string(request.major) + "." +
                 std::to_string(request.minor) + ": " + why + ";";
        log(LogLevel::debug, std::string("engine::Window: ") + request.platform + " context failed: " + why);
    }
    return nullptr;
}

// Opens a context of any version to report what the driver offers, then fails.
[[noreturn]] void fail_without_gl43(const std::string& title, const std::string& tried) {
    for (const ContextRequest& request : {ContextRequest{GLFW_EGL_CONTEXT_API, 0, 0, "glfw-egl"},
                                          ContextRequest{GLFW_NATIVE_CONTEXT_API, 0, 0, "glfw-glx"}}) {
        GLFWwindow* probe = open_window(request, title, 64, 64);
        if (probe == nullptr) continue;
        glfwMakeContextCurrent(probe);
        const GlInfo info = query_current_gl_info(request.platform);
        glfwMakeContextCurrent(nullptr);
        glfwDestroyWindow(probe);
        release_glfw();
        fail("OpenGL 4.3 core with compute shaders is required; found OpenGL " + info.version + " on '" +
             info.renderer + "' (" + info.vendor + ") through " + request.platform);
    }
    release_glfw();
    fail("engine::Window: no OpenGL context could be created (tried:" + tried + ")");
}

int glfw_key(Key key) {
    switch (key) {
        case Key::w:
            return GLFW_KEY_W;
        case Key::a:
            return GLFW_KEY_A;
        case Key::s:
            return GLFW_KEY_S;
        case Key::d:
            return GLFW_KEY_D;
        case Key::q:
            return GLFW_KEY_Q;
        case Key::e:
            return GLFW_KEY_E;
        case Key::left_shift:
            return GLFW_KEY_LEFT_SHIFT;
        case Key::escape:
            return GLFW_KEY_ESCAPE;
        case Key::f1:
            return GLFW_KEY_F1;
        case Key::space:
            return GLFW_KEY_SPACE;
    }
    return GLFW_KEY_UNKNOWN;
}

int glfw_button(MouseButton button) {
    switch (button) {
        case MouseButton::left:
            return GLFW_MOUSE_BUTTON_LEFT;
        case MouseButton::right:
            return GLFW_MOUSE_BUTTON_RIGHT;
        case MouseButton::middle:
            return GLFW_MOUSE_BUTTON_MIDDLE;
    }
    return GLFW_MOUSE_BUTTON_LEFT;
}

}  // namespace

std::unique_ptr<Window> Window::create(const std::string& title, int width, int height, bool vsync) {
    if (width <= 0 || height <= 0)
        fail("engine::Window: size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
    acquire_glfw();
    std::string platform, tried;
    GLFWwindow* handle = open_gl45_window(title, width, height, platform, tried);
    if (handle == nullptr) fail_without_gl43(title, tried);

    // From here the Window owns the handle and the GLFW reference, also when a check throws.
    std::unique_ptr<Window> window(new Window());
    window->window_ = handle;
    glfwMakeContextCurrent(handle);
    glfwSwapInterval(vsync ? 1 : 0);
    window->info_ = query_current_gl_info(platform);
    require_compute_support(window->info_);
    if (gl_debug_requested()) install_gl_debug_output();

    // Installed before ImGui's backend, which chains to callbacks already present.
    glfwSetWindowUserPointer(handle, window.get());
    glfwSetScrollCallback(handle, &Window::scroll_callback);
    log(LogLevel::debug, "GL " + window->info_.version + " on " + window->info_.renderer + " (" + platform + ")");
    return window;
}

Window::~Window() {
    if (window_ == nullptr) return;
    if (glfwGetCurrentContext() == window_) glfwMakeContextCurrent(nullptr);
    glfwDestroyWindow(window_);
    release_glfw();
}

bool Window::should_close() const {
    return glfwWindowShouldClose(window_) == GLFW_TRUE;
}

void Window::request_close() {
    glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

void Window::poll_events() {
    glfwPollEvents();
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window_, &x, &y);
    const glm::vec2 position(static_cast<float>(x), static_cast<float>(y));
    // The first sample has nothing to compare with; a jump from (0, 0) would spin the camera.
    mouse_delta_ = have_mouse_position_ ? position - mouse_position_ : glm::vec2(0.0f);
    mouse_position_ = position;
    have_mouse_position_ = true;
    scroll_delta_ = scroll_accumulated_;
    scroll_accumulated_ = 0.0f;
}

void Window::swap_buffers() {
    glfwSwapBuffers(window_);
}

glm::vec2 Window::cursor_pixel() const {
    int width = 0, height = 0;
    glfwGetWindowSize(window_, &width, &height);
    const glm::ivec2 framebuffer = framebuffer_size();
    if (width <= 0 || height <= 0) return mouse_position_;
    return mouse_position_ * glm::vec2(framebuffer) / glm::vec2(width, height);
}

glm::ivec2 Window::framebuffer_size() const {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    return {width, height};
}

bool Window::key_down(Key key) const {
    return glfwGetKey(window_, glfw_key(key)) == GLFW_PRESS;
}

bool Window::mouse_down(MouseButton button) const {
    return glfwGetMouseButton(window_, glfw_button(button)) == GLFW_PRESS;
}

void Window::scroll_callback(GLFWwindow* handle, double, double y) {
    if (auto* self = static_cast<Window*>(glfwGetWindowUserPointer(handle)))
        self->scroll_accumulated_ += static_cast<float>(y);
}

}  // namespace engine
