#pragma once
// Move-only RAII owners of OpenGL objects. Each type can exist empty (NoCreate) before a
// context does, carries a debug label visible in GL debuggers and KHR_debug messages, and
// hands its name over with release() for interop.
#include <cstddef>
#include <string_view>
#include <utility>

#include "engine/gl/gl.h"

namespace engine::gl {

struct NoCreateT {
    explicit constexpr NoCreateT() = default;
};
inline constexpr NoCreateT NoCreate{};

// Kind describes how to create and destroy one object type and its KHR_debug identifier.
template <class Kind>
class Object {
public:
    explicit Object(NoCreateT) noexcept {}
    explicit Object(std::string_view label = {}) : id_(Kind::create()) { set_label(label); }
    ~Object() { reset(); }

    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;
    Object(Object&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Object& operator=(Object&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }

    GLuint id() const noexcept { return id_; }
    explicit operator bool() const noexcept { return id_ != 0; }
    // Gives up ownership: the caller deletes the returned name.
    GLuint release() noexcept { return std::exchange(id_, 0); }
    void reset() noexcept {
        if (id_ != 0) Kind::destroy(id_);
        id_ = 0;
    }
    void set_label(std::string_view label) {
        if (id_ != 0 && !label.empty())
            glObjectLabel(Kind::identifier, id_, static_cast<GLsizei>(label.size()), label.data());
    }

protected:
    GLuint id_ = 0;
};

namespace kinds {
struct Buffer {
    static constexpr GLenum identifier = GL_BUFFER;
    static GLuint create() {
        GLuint id = 0;
        glCreateBuffers(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct VertexArray {
    static constexpr GLenum identifier = GL_VERTEX_ARRAY;
    static GLuint create() {
        GLuint id = 0;
        glCreateVertexArrays(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct Framebuffer {
    static constexpr GLenum identifier = GL_FRAMEBUFFER;
    static GLuint create() {
        GLuint id = 0;
        glCreateFramebuffers(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct Program {
    static constexpr GLenum identifier = GL_PROGRAM;
    static GLuint create() { return glCreateProgram(); }
    static void destroy(GLuint id) { glDeleteProgram(id); }
};
struct Sampler {
    static constexpr GLenum identifier = GL_SAMPLER;
    static GLuint create() {
        GLuint id = 0;
        glCreateSamplers(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteSamplers(1, &id); }
};
}  // namespace kinds

// A buffer with immutable-size storage; grow() reallocates (contents are not kept).
class Buffer : public Object<kinds::Buffer> {
public:
    using Object::Object;
    void storage(std::size_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
    void upload(std::size_t offset, std::size_t bytes, const void* data);
    std::size_t size() const noexcept { return size_; }
    // Recreates the buffer with at least `bytes` (grown by 1.5x steps, rounded up to 16 bytes so
    // that any clear format divides the size) when it is too small. Returns true when it reallocated.
    bool ensure_size(std::size_t bytes, std::string_view label, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);

private:
    std::size_t size_ = 0;
};

class Texture {
public:
    explicit Texture(NoCreateT) noexcept {}
    Texture(GLenum target, std::string_view label);
    ~Texture() { reset(); }
    Texture(const Texture&) = delete;
    Texture& operator=(const Texture&) = delete;
    Texture(Texture&& o) noexcept : id_(std::exchange(o.id_, 0)), target_(o.target_) {}
    Texture& operator=(Texture&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, 0);
            target_ = o.target_;
        }
        return *this;
    }
    GLuint id() const noexcept { return id_; }
    GLenum target() const noexcept { return target_; }
    explicit operator bool() const noexcept { return id_ != 0; }
    GLuint release() noexcept { return std::exchange(id_, 0); }
    void reset() noexcept;

private:
    GLuint id_ = 0;
    GLenum target_ = GL_TEXTURE_2D;
};

class Query {
public:
    explicit Query(NoCreateT) noexcept {}
    Query(GLenum target, std::string_view label);
    ~Query() { reset(); }
    Query(const Query&) = delete;
    Query& operator=(const Query&) = delete;
    Query(Query&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
    Query& operator=(Query&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, 0);
        }
        return *this;
    }
    GLuint id() const noexcept { return id_; }
    void reset() noexcept;

private:
    GLuint id_ = 0;
};

// A fence sync object: signalled once the GPU has passed the point where it was inserted.
class Fence {
public:
    Fence() noexcept = default;
    ~Fence() { reset(); }
    Fence(const Fence&) = delete;
    Fence& operator=(const Fence&) = delete;
    Fence(Fence&& o) noexcept : sync_(std::exchange(o.sync_, nullptr)) {}
    Fence& operator=(Fence&& o) noexcept {
        if (this != &o) {
            reset();
            sync_ = std::exchange(o.sync_, nullptr);
        }
        return *this;
    }
    void insert();
    bool signalled() const;  // never blocks
    bool pending() const noexcept { return sync_ != nullptr; }
    void reset() noexcept;

private:
    GLsync sync_ = nullptr;
};

using VertexArray = Object<kinds::VertexArray>;
using Framebuffer = Object<kinds::Framebuffer>;
using Program = Object<kinds::Program>;
using Sampler = Object<kinds::Sampler>;

}  // namespace engine::gl
