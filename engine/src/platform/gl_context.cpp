#include "engine/platform/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/log.h"

namespace engine {
namespace {

std::string egl_error_name(EGLint code) {
    switch (code) {
        case EGL_SUCCESS:
            return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        default:
            return "EGL error " + std::to_string(code);
    }
}

bool has_extension(const char* list, const char* name) {
    if (list == nullptr) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    }
    return false;
}

struct DisplayChoice {
    EGLDisplay display = EGL_NO_DISPLAY;
    std::string platform;
};

// Mesa's surfaceless platform needs no window system and no device node.
DisplayChoice open_surfaceless(std::string& tried) {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!has_extension(client, "EGL_MESA_platform_surfaceless")) {
        tried += " surfaceless: extension missing;";
        return {};
    }
    EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor)) {
        tried += " surfaceless: " + egl_error_name(eglGetError()) + ";";
        return {};
    }
    return {d, "surfaceless"};
}

// NVIDIA's driver exposes GPUs as EGL devices; take the first one that initialises.
DisplayChoice open_device(std::string& tried) {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!has_extension(client, "EGL_EXT_platform_device")) {
        tried += " device: extension missing;";
        return {};
    }
    EGLint count = 0;
    if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) {
        tried += " device: no EGL devices;";
        return {};
    }
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    eglQueryDevicesEXT(count, devices.data(), &count);
    for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(i)], nullptr);
        EGLint major = 0, minor = 0;
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return {d, "device"};
    }
    tried += " device: no device initialised;";
    return {};
}

}  // namespace

void require_compute_support(const GlInfo& info) {
    const bool ok = info.major > 4 || (info.major == 4 && info.minor >= 3);
    if (!ok) {
        fail("OpenGL 4.3 with compute shaders is required; found OpenGL " + info.version + " on '" + info.renderer +
             "' (" + info.vendor + ") through " + info.platform);
    }
}

bool gl_debug_requested() {
#ifndef NDEBUG
    return true;
#else
    const char* env = std::getenv("ENGINE_GL_DEBUG");
    return env != nullptr && env[0] == '1';
#endif
}

std::unique_ptr<HeadlessGlContext> HeadlessGlContext::create(bool debug) {
    std::string tried;
    DisplayChoice choice = open_surfaceless(tried);
    if (choice.display == EGL_NO_DISPLAY) choice = open_device(tried);
    if (choice.display == EGL_NO_DISPLAY) fail("headless OpenGL: no usable EGL display (tried:" + tried + ")");

    if (!eglBindAPI(EGL_OPENGL_API))
        fail("headless OpenGL: eglBindAPI(EGL_OPENGL_API) failed: " + egl_error_name(eglGetError()));
    const char* display_ext = eglQueryString(choice.display, EGL_EXTENSIONS);
    if (!has_extension(display_ext, "EGL_KHR_no_config_context") &&
        !has_extension(display_ext, "EGL_MESA_configless_context"))
        fail("headless OpenGL: EGL display (" + choice.platform + ") lacks EGL_KHR_no_config_context");

    // Ask for 4.5 first, then the 4.3 minimum so that the error below can say what was found.
    EGLContext context = EGL_NO_CONTEXT;
    for (EGLint minor : {5, 3}) {
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     minor,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG,
                                     debug ? EGL_TRUE : EGL_FALSE,
                                     EGL_NONE};
        context = eglCreateContext(choice.display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
        if (context != EGL_NO_CONTEXT) break;
    }
    if (context == EGL_NO_CONTEXT) {
        // Report what the driver can do, from a context of any version.
        const EGLint any[] = {EGL_NONE};
        EGLContext probe = eglCreateContext(choice.display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, any);
        std::string found = "no OpenGL context at all";
        if (probe != EGL_NO_CONTEXT && eglMakeCurrent(choice.display, EGL_NO_SURFACE, EGL_NO_SURFACE, probe)) {
            const GlInfo info = query_current_gl_info(choice.platform);
            found = "OpenGL " + info.version + " on '" + info.renderer + "'";
            eglMakeCurrent(choice.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(choice.display, probe);
        }
        eglTerminate(choice.display);
        fail("OpenGL 4.3 core with compute shaders is required; found " + found + " through EGL " + choice.platform);
    }
    if (!eglMakeCurrent(choice.display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
        fail("headless OpenGL: eglMakeCurrent failed: " + egl_error_name(eglGetError()));

    std::unique_ptr<HeadlessGlContext> result(new HeadlessGlContext());
    result->display_ = choice.display;
    result->context_ = context;
    result->info_ = query_current_gl_info(choice.platform);
    require_compute_support(result->info_);
    if (debug) install_gl_debug_output();
    log(LogLevel::debug,
        "GL " + result->info_.version + " on " + result->info_.renderer + " (EGL " + choice.platform + ")");
    return result;
}

void HeadlessGlContext::make_current() {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_);
}

HeadlessGlContext::~HeadlessGlContext() {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    // The display is shared per process by EGL; terminating it would also end other contexts.
}

}  // namespace engine
