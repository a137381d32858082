#pragma once
// What the GL driver holds for the current context, found by asking the driver (glIs*, object
// parameters), not from the engine's own bookkeeping: the live objects of each kind and the bytes of
// buffer and texture storage. A soak run compares censuses taken at the same point of a repeated
// walk; anything that grows from one to the next is a leak. Needs a current context; costs a few
// thousand glIs* calls (a millisecond or so), so take it at checkpoints, not every frame.
#include <cstdint>
#include <string>

namespace engine::gl {

struct GlCensus {
    std::uint32_t buffers = 0, textures = 0, vertex_arrays = 0, framebuffers = 0, renderbuffers = 0;
    std::uint32_t programs = 0, shaders = 0, samplers = 0, queries = 0;
    std::uint64_t buffer_bytes = 0;   // GL_BUFFER_SIZE summed over the live buffers
    std::uint64_t texture_bytes = 0;  // every level (and cube face) at the texel size of its format

    std::uint32_t objects() const;
    // "buffers 12 (3.1 MiB), textures 4 (1.0 MiB), vertex arrays 2, ..."
    std::string describe() const;
    bool same_objects(const GlCensus& other) const;
};

// Names are scanned from 1 until `gap` consecutive names in a row are not objects of the kind
// (drivers hand out the lowest free names, so live ones stay packed near the start).
GlCensus take_gl_census(std::uint32_t gap = 1024);

}  // namespace engine::gl
