#include "engine/gl/gl_census.h"

#include <array>
#include <cstdio>

#include "engine/gl/gl.h"

namespace engine::gl {
namespace {

template <class IsObject, class Visit>
std::uint32_t scan(std::uint32_t gap, IsObject is_object, Visit visit) {
    std::uint32_t count = 0, misses = 0;
    for (GLuint name = 1; misses < gap; ++name) {
        if (is_object(name) == GL_TRUE) {
            ++count;
            misses = 0;
            visit(name);
        } else {
            ++misses;
        }
    }
    return count;
}

std::uint64_t level_bytes(GLuint texture, GLint level, GLenum target) {
    GLint width = 0, height = 0, depth = 0, compressed = 0;
    glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_WIDTH, &width);
    if (width <= 0) return 0;
    glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_HEIGHT, &height);
    glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_DEPTH, &depth);
    glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_COMPRESSED, &compressed);
    const std::uint64_t faces = target == GL_TEXTURE_CUBE_MAP ? 6 : 1;
    if (compressed == GL_TRUE) {
        GLint size = 0;
        glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_COMPRESSED_IMAGE_SIZE, &size);
        return faces * static_cast<std::uint64_t>(size);
    }
    std::uint64_t bits = 0;
    for (const GLenum component : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE,
                                   GL_TEXTURE_ALPHA_SIZE, GL_TEXTURE_DEPTH_SIZE, GL_TEXTURE_STENCIL_SIZE}) {
        GLint size = 0;
        glGetTextureLevelParameteriv(texture, level, component, &size);
        bits += static_cast<std::uint64_t>(size);
    }
    return faces * static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) *
           static_cast<std::uint64_t>(depth > 0 ? depth : 1) * bits / 8;
}

std::uint64_t texture_bytes(GLuint texture) {
    GLint target = 0;
    glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
    if (target == 0 || target == GL_TEXTURE_BUFFER) return 0;  // unspecified, or storage counted as a buffer
    std::uint64_t bytes = 0;
    for (GLint level = 0; level < 16; ++level) {
        const std::uint64_t b = level_bytes(texture, level, static_cast<GLenum>(target));
        if (b == 0) break;
        bytes += b;
    }
    return bytes;
}

double mib(std::uint64_t bytes) {
    return static_cast<double>(bytes) / (1024.0 * 1024.0);
}

}  // namespace

std::uint32_t GlCensus::objects() const {
    return buffers + textures + vertex_arrays + framebuffers + renderbuffers + programs + shaders + samplers + queries;
}

bool GlCensus::same_objects(const GlCensus& o) const {
    return buffers == o.buffers && textures == o.textures && vertex_arrays == o.vertex_arrays &&
           framebuffers == o.framebuffers && renderbuffers == o.renderbuffers && programs == o.programs &&
           shaders == o.shaders && samplers == o.samplers && queries == o.queries;
}

std::string GlCensus::describe() const {
    char text[320];
    std::snprintf(text, sizeof text,
                  "buffers %u (%.2f MiB), textures %u (%.2f MiB), vertex arrays %u, framebuffers %u, "
                  "renderbuffers %u, programs %u, shaders %u, samplers %u, queries %u",
                  buffers, mib(buffer_bytes), textures, mib(texture_bytes), vertex_arrays, framebuffers, renderbuffers,
                  programs, shaders, samplers, queries);
    return text;
}

GlCensus take_gl_census(std::uint32_t gap) {
    GlCensus c;
    const auto none = [](GLuint) {};
    c.buffers = scan(
        gap, [](GLuint n) { return glIsBuffer(n); },
        [&](GLuint n) {
            GLint64 size = 0;
            glGetNamedBufferParameteri64v(n, GL_BUFFER_SIZE, &size);
            c.buffer_bytes += static_cast<std::uint64_t>(size);
        });
    c.textures = scan(
        gap, [](GLuint n) { return glIsTexture(n); }, [&](GLuint n) { c.texture_bytes += texture_bytes(n); });
    c.vertex_arrays = scan(
        gap, [](GLuint n) { return glIsVertexArray(n); }, none);
    c.framebuffers = scan(
        gap, [](GLuint n) { return glIsFramebuffer(n); }, none);
    c.renderbuffers = scan(
        gap, [](GLuint n) { return glIsRenderbuffer(n); }, none);
    c.programs = scan(
        gap, [](GLuint n) { return glIsProgram(n); }, none);
    c.shaders = scan(
        gap, [](GLuint n) { return glIsShader(n); }, none);
    c.samplers = scan(
        gap, [](GLuint n) { return glIsSampler(n); }, none);
    c.queries = scan(
        gap, [](GLuint n) { return glIsQuery(n); }, none);
    return c;
}

}  // namespace engine::gl
