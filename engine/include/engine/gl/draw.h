#pragma once
// The raster side of the GL layer, as compute_step.h is the compute side: vertex arrays, textures made
// from images, uniforms set by name, and an opaque depth-tested raster into a framebuffer, so that a
// raster pass (the mesh pass) never calls GL itself.
#include <cstdint>
#include <span>
#include <string_view>

#include <glm/glm.hpp>

#include "engine/gl/objects.h"

namespace engine::gl {

// One float attribute of an interleaved vertex: `floats` components at `offset` bytes into the vertex.
struct VertexAttribute {
    GLuint location = 0;
    GLint floats = 0;
    GLuint offset = 0;
};
// An indexed vertex array over one interleaved vertex buffer of `stride` bytes per vertex.
VertexArray vertex_array(const Buffer& vertices, GLsizei stride, const Buffer& indices,
                         std::span<const VertexAttribute> attributes, std::string_view label);

// An sRGB-encoded RGBA8 image (rows tightly packed) as a texture with its full mip chain, sampled
// trilinearly and repeating; sampling returns linear values.
Texture srgb_texture(int width, int height, const std::uint8_t* rgba, std::string_view label);

// A uniform of `program`, its location looked up once (−1, and setting it does nothing, when the program
// has none of that name): look it up before a loop of draws, not in it.
struct Uniform {
    const Program* program = nullptr;
    GLint location = -1;
};
Uniform uniform(const Program& program, const char* name);
void set_uniform(const Uniform& uniform, const glm::mat4& value);
void set_uniform(const Uniform& uniform, const glm::mat3& value);
void set_uniform(const Uniform& uniform, const glm::vec4& value);
void set_uniform(const Uniform& uniform, const glm::vec3& value);
void set_uniform(const Uniform& uniform, std::span<const glm::vec3> values);
void set_uniform(const Uniform& uniform, int value);
void set_uniform(const Uniform& uniform, float value);
// Once, by name.
template <class T>
void set_uniform(const Program& program, const char* name, const T& value) {
    set_uniform(uniform(program, name), value);
}

// An opaque raster into `framebuffer` (`width` × `height`) with `program`: depth test (less), no blending,
// no face culling, clockwise front faces when `clockwise_front` (a target whose Y is flipped). The state
// is restored (no program, no framebuffer, no depth test, counter-clockwise fronts) when it ends.
class RasterScope {
public:
    RasterScope(const Program& program, const Framebuffer& framebuffer, int width, int height, bool clockwise_front);
    ~RasterScope();
    RasterScope(const RasterScope&) = delete;
    RasterScope& operator=(const RasterScope&) = delete;

    // The triangles of `vertices` (32-bit indices), with `texture` on `texture_unit` when there is one.
    void draw_triangles(const VertexArray& vertices, GLsizei index_count, const Texture* texture,
                        GLuint texture_unit) const;
};

}  // namespace engine::gl
