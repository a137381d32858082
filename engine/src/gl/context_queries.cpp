// The GL side of the platform's contexts (engine/platform/gl_context.h): what the current context is, and
// its debug output. Here, in the GL layer, so that no other code calls GL.
#include <string>

#include "engine/core/log.h"
#include "engine/gl/gl.h"
#include "engine/platform/gl_context.h"

namespace engine {

GlInfo query_current_gl_info(const std::string& platform) {
    GlInfo info;
    auto str = [](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(glGetString(name));
        return std::string(s ? s : "?");
    };
    info.vendor = str(GL_VENDOR);
    info.renderer = str(GL_RENDERER);
    info.version = str(GL_VERSION);
    info.platform = platform;
    glGetIntegerv(GL_MAJOR_VERSION, &info.major);
    glGetIntegerv(GL_MINOR_VERSION, &info.minor);
    return info;
}

namespace {

void GLAPIENTRY debug_callback(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* message,
                               const void*) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    const std::string text = "GL[" + std::to_string(id) + "] " + message;
    if (severity == GL_DEBUG_SEVERITY_HIGH || type == GL_DEBUG_TYPE_ERROR)
        log_error(text);
    else
        log_warning(text);
}

}  // namespace

void install_gl_debug_output() {
    if (!epoxy_has_gl_extension("GL_KHR_debug") && epoxy_gl_version() < 43) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_callback, nullptr);
}

}  // namespace engine
