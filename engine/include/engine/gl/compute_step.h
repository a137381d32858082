#pragma once
// A compute step of a GPU frame as data: the resources it binds, its program, its dispatch (a grid of
// work groups, or the arguments a buffer holds) and the memory barrier that makes its writes visible
// to what follows. A pass describes its steps and run() records them, so that the pass itself never
// calls GL; the few buffer, texture and driver operations a frame needs around its steps are here too.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "engine/gl/objects.h"

namespace engine::gl {

// Work groups of `size` that cover `count` items.
constexpr std::uint32_t groups_for(std::uint32_t count, std::uint32_t size) {
    return (count + size - 1) / size;
}

// A buffer at an indexed binding point: a shader storage block (the default) or a uniform block.
struct BufferBinding {
    GLuint index = 0;
    const Buffer* buffer = nullptr;
    GLenum target = GL_SHADER_STORAGE_BUFFER;
};
// Level 0 of a texture as an image unit, read and written in `format`.
struct ImageBinding {
    GLuint unit = 0;
    const Texture* texture = nullptr;
    GLenum format = GL_RGBA8;
};
// A texture on a texture unit, for sampling or texel fetches.
struct TextureBinding {
    GLuint unit = 0;
    const Texture* texture = nullptr;
};
// Everything a set of steps binds; each is bound in the order given.
struct Bindings {
    std::span<const BufferBinding> buffers;
    std::span<const ImageBinding> images;
    std::span<const TextureBinding> textures;
};
void bind(const Bindings& bindings);

struct ComputeStep {
    const Program* program = nullptr;
    glm::uvec3 groups{1, 1, 1};        // the grid, when `indirect` is null
    const Buffer* indirect = nullptr;  // else the dispatch arguments (3 uints) at `indirect_offset` of this buffer
    std::size_t indirect_offset = 0;
    GLbitfield barrier = 0;  // glMemoryBarrier bits after the dispatch (0: none)
};
// Uses the step's program and dispatches it, then issues its barrier. The bindings are the caller's.
void run(const ComputeStep& step);
// Leaves no program in use (after the last step of a frame).
void end_steps();
void memory_barrier(GLbitfield bits);
// Waits until the GPU has done everything recorded so far (for timing a frame).
void finish();

// Buffer contents: every word zero; a copy of the first `bytes`; `bytes` from `offset` read back
// (waits for the GPU).
void clear_to_zero(const Buffer& buffer);
void copy_buffer(const Buffer& from, const Buffer& to, std::size_t bytes);
void read_buffer(const Buffer& buffer, std::size_t offset, std::size_t bytes, void* out);

// A 2D texture with one level of `internal_format` storage; level 0 read back as floats of `format`
// (GL_RGBA, GL_RED), `floats` of them (waits for the GPU).
Texture texture_2d(GLenum internal_format, int width, int height, std::string_view label);
// Copies level 0 of `from` into `to`, two 2D textures of the same size and format.
void copy_texture(const Texture& from, const Texture& to, int width, int height);
void read_texture(const Texture& texture, GLenum format, std::size_t floats, float* out);

// What a pass may choose by: the GL renderer's name, whether it is a CPU rasteriser (llvmpipe,
// softpipe), and the most texels a buffer texture may have.
struct DriverLimits {
    std::string renderer;
    bool cpu_rasteriser = false;
    std::int64_t max_texture_buffer_texels = 0;
};
DriverLimits driver_limits();

}  // namespace engine::gl
