#pragma once
// A headless OpenGL 4.5 core context through EGL, current on the creating thread.
// Tries Mesa's surfaceless platform first, then the EGL device platform that NVIDIA drivers
// offer; rendering goes to the engine's own framebuffers (there is no default surface).
#include <memory>
#include <string>

namespace engine {

struct GlInfo {
    std::string vendor;
    std::string renderer;
    std::string version;
    std::string platform;  // "surfaceless", "device", "glfw-egl", "glfw-glx"
    int major = 0;
    int minor = 0;
};

// Throws engine::Error naming what was found when the current context lacks GL 4.3 compute
// shaders (the minimum for the splat passes).
GlInfo query_current_gl_info(const std::string& platform);
void require_compute_support(const GlInfo& info);

// Installs a KHR_debug callback that routes driver messages to the log (debug builds, or when
// ENGINE_GL_DEBUG=1). High-severity messages are logged as errors.
void install_gl_debug_output();
// True in debug builds or when ENGINE_GL_DEBUG=1.
bool gl_debug_requested();

class HeadlessGlContext {
public:
    // Creates the context and makes it current. `debug` requests a debug context with KHR_debug
    // output routed to the log (on in debug builds; ENGINE_GL_DEBUG=1 turns it on anywhere).
    static std::unique_ptr<HeadlessGlContext> create(bool debug = gl_debug_requested());
    ~HeadlessGlContext();
    HeadlessGlContext(const HeadlessGlContext&) = delete;
    HeadlessGlContext& operator=(const HeadlessGlContext&) = delete;

    const GlInfo& info() const { return info_; }
    void make_current();

private:
    HeadlessGlContext() = default;
    void* display_ = nullptr;
    void* context_ = nullptr;
    GlInfo info_;
};

}  // namespace engine
