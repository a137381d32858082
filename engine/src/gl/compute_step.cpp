// Compute steps as data (compute_step.h).
#include "engine/gl/compute_step.h"

namespace engine::gl {

void bind(const Bindings& bindings) {
    for (const BufferBinding& b : bindings.buffers) glBindBufferBase(b.target, b.index, b.buffer->id());
    for (const ImageBinding& i : bindings.images)
        glBindImageTexture(i.unit, i.texture->id(), 0, GL_FALSE, 0, GL_READ_WRITE, i.format);
    for (const TextureBinding& t : bindings.textures) glBindTextureUnit(t.unit, t.texture->id());
}

void run(const ComputeStep& step) {
    glUseProgram(step.program->id());
    if (step.indirect != nullptr) {
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, step.indirect->id());
        glDispatchComputeIndirect(static_cast<GLintptr>(step.indirect_offset));
    } else {
        glDispatchCompute(step.groups.x, step.groups.y, step.groups.z);
    }
    if (step.barrier != 0) glMemoryBarrier(step.barrier);
}

void end_steps() {
    glUseProgram(0);
}

void memory_barrier(GLbitfield bits) {
    glMemoryBarrier(bits);
}

void finish() {
    glFinish();
}

void clear_to_zero(const Buffer& buffer) {
    glClearNamedBufferData(buffer.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
}

void copy_buffer(const Buffer& from, const Buffer& to, std::size_t bytes) {
    glCopyNamedBufferSubData(from.id(), to.id(), 0, 0, static_cast<GLsizeiptr>(bytes));
}

void read_buffer(const Buffer& buffer, std::size_t offset, std::size_t bytes, void* out) {
    glGetNamedBufferSubData(buffer.id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), out);
}

Texture texture_2d(GLenum internal_format, int width, int height, std::string_view label) {
    Texture texture(GL_TEXTURE_2D, label);
    glTextureStorage2D(texture.id(), 1, internal_format, width, height);
    return texture;
}

void copy_texture(const Texture& from, const Texture& to, int width, int height) {
    glCopyImageSubData(from.id(), GL_TEXTURE_2D, 0, 0, 0, 0, to.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
}

void read_texture(const Texture& texture, GLenum format, std::size_t floats, float* out) {
    glGetTextureImage(texture.id(), 0, format, GL_FLOAT, static_cast<GLsizei>(floats * sizeof(float)), out);
}

DriverLimits driver_limits() {
    DriverLimits limits;
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    limits.renderer = renderer != nullptr ? renderer : "";
    limits.cpu_rasteriser =
        limits.renderer.find("llvmpipe") != std::string::npos || limits.renderer.find("softpipe") != std::string::npos;
    GLint texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
    limits.max_texture_buffer_texels = texels;
    return limits;
}

}  // namespace engine::gl
