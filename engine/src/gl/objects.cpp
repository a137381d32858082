#include "engine/gl/objects.h"

#include <algorithm>
#include <string>

namespace engine::gl {

void Buffer::storage(std::size_t bytes, const void* data, GLbitfield flags) {
    // Immutable storage cannot be respecified: make a fresh buffer name for the new size.
    if (id_ != 0) {
        std::string label(256, '\0');
        GLsizei length = 0;
        glGetObjectLabel(GL_BUFFER, id_, static_cast<GLsizei>(label.size()), &length, label.data());
        label.resize(static_cast<std::size_t>(length));
        reset();
        id_ = kinds::Buffer::create();
        set_label(label);
    } else {
        id_ = kinds::Buffer::create();
    }
    glNamedBufferStorage(id_, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 4)), data, flags);
    size_ = bytes;
}

void Buffer::upload(std::size_t offset, std::size_t bytes, const void* data) {
    glNamedBufferSubData(id_, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

bool Buffer::ensure_size(std::size_t bytes, std::string_view label, GLbitfield flags) {
    if (id_ != 0 && size_ >= bytes) return false;
    // Whole 16-byte units: glClearNamedBufferData refuses (GL_INVALID_VALUE, nothing cleared) a size
    // that is not a multiple of its format's size, and a 1.5x step of a 4-byte multiple need not be one.
    const std::size_t grown = (std::max(bytes, size_ + size_ / 2) + 15) / 16 * 16;
    reset();
    id_ = kinds::Buffer::create();
    set_label(label);
    glNamedBufferStorage(id_, static_cast<GLsizeiptr>(std::max<std::size_t>(grown, 4)), nullptr, flags);
    size_ = grown;
    return true;
}

Texture::Texture(GLenum target, std::string_view label) : target_(target) {
    glCreateTextures(target, 1, &id_);
    if (!label.empty()) glObjectLabel(GL_TEXTURE, id_, static_cast<GLsizei>(label.size()), label.data());
}

void Texture::reset() noexcept {
    if (id_ != 0) glDeleteTextures(1, &id_);
    id_ = 0;
}

Query::Query(GLenum target, std::string_view label) {
    glCreateQueries(target, 1, &id_);
    if (!label.empty()) glObjectLabel(GL_QUERY, id_, static_cast<GLsizei>(label.size()), label.data());
}

void Query::reset() noexcept {
    if (id_ != 0) glDeleteQueries(1, &id_);
    id_ = 0;
}

void Fence::insert() {
    reset();
    sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

bool Fence::signalled() const {
    if (sync_ == nullptr) return true;
    GLint status = GL_UNSIGNALED;
    glGetSynciv(sync_, GL_SYNC_STATUS, 1, nullptr, &status);
    return status == GL_SIGNALED;
}

void Fence::reset() noexcept {
    if (sync_ != nullptr) glDeleteSync(sync_);
    sync_ = nullptr;
}

}  // namespace engine::gl
