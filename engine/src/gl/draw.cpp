// The raster side of the GL layer (draw.h).
#include "engine/gl/draw.h"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>

namespace engine::gl {

VertexArray vertex_array(const Buffer& vertices, GLsizei stride, const Buffer& indices,
                         std::span<const VertexAttribute> attributes, std::string_view label) {
    VertexArray array(label);
    const GLuint vao = array.id();
    glVertexArrayVertexBuffer(vao, 0, vertices.id(), 0, stride);
    glVertexArrayElementBuffer(vao, indices.id());
    for (const VertexAttribute& a : attributes) {
        glEnableVertexArrayAttrib(vao, a.location);
        glVertexArrayAttribFormat(vao, a.location, a.floats, GL_FLOAT, GL_FALSE, a.offset);
        glVertexArrayAttribBinding(vao, a.location, 0);
    }
    return array;
}

Texture srgb_texture(int width, int height, const std::uint8_t* rgba, std::string_view label) {
    Texture t(GL_TEXTURE_2D, label);
    int levels = 1;
    for (int s = std::max(width, height); s > 1; s /= 2) ++levels;
    glTextureStorage2D(t.id(), levels, GL_SRGB8_ALPHA8, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(t.id(), 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glGenerateTextureMipmap(t.id());
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    return t;
}

Uniform uniform(const Program& program, const char* name) {
    return {&program, glGetUniformLocation(program.id(), name)};
}

void set_uniform(const Uniform& u, const glm::mat4& value) {
    glProgramUniformMatrix4fv(u.program->id(), u.location, 1, GL_FALSE, glm::value_ptr(value));
}
void set_uniform(const Uniform& u, const glm::mat3& value) {
    glProgramUniformMatrix3fv(u.program->id(), u.location, 1, GL_FALSE, glm::value_ptr(value));
}
void set_uniform(const Uniform& u, const glm::vec4& value) {
    glProgramUniform4fv(u.program->id(), u.location, 1, glm::value_ptr(value));
}
void set_uniform(const Uniform& u, const glm::vec3& value) {
    glProgramUniform3fv(u.program->id(), u.location, 1, glm::value_ptr(value));
}
void set_uniform(const Uniform& u, std::span<const glm::vec3> values) {
    if (values.empty()) return;
    glProgramUniform3fv(u.program->id(), u.location, static_cast<GLsizei>(values.size()), glm::value_ptr(values[0]));
}
void set_uniform(const Uniform& u, int value) {
    glProgramUniform1i(u.program->id(), u.location, value);
}

void set_uniform(const Uniform& u, float value) {
    glProgramUniform1f(u.program->id(), u.location, value);
}

RasterScope::RasterScope(const Program& program, const Framebuffer& framebuffer, int width, int height,
                         bool clockwise_front) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glFrontFace(clockwise_front ? GL_CW : GL_CCW);
    glUseProgram(program.id());
}

RasterScope::~RasterScope() {
    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glFrontFace(GL_CCW);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void RasterScope::draw_triangles(const VertexArray& vertices, GLsizei index_count, const Texture* texture,
                                 GLuint texture_unit) const {
    if (texture != nullptr) glBindTextureUnit(texture_unit, texture->id());
    glBindVertexArray(vertices.id());
    glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);
}

}  // namespace engine::gl
