#pragma once
// Buffer-texture views of storage buffers, for the passes that read their inputs with texel fetches
// on CPU drivers (docs/algorithms.md §1, "Raster").
#include "engine/gl/objects.h"

namespace engine::gl {

// Points `view` (made on first use, named `label`) at the whole of `buffer` as texels of `format` and
// binds it to texture unit `unit`. Called each frame: buffers are reallocated when they grow. The
// caller issues GL_TEXTURE_FETCH_BARRIER_BIT once the buffers' writes are done.
inline void bind_buffer_texture(Texture& view, const char* label, GLenum format, const Buffer& buffer, GLuint unit) {
    if (!view) view = Texture(GL_TEXTURE_BUFFER, label);
    glTextureBuffer(view.id(), format, buffer.id());
    glBindTextureUnit(unit, view.id());
}

}  // namespace engine::gl
