// The render target (engine/render/render_target.h): a framebuffer with its colour, depth and view-depth
// textures, their clears and read-backs, and presenting it to a window. A GL resource, so it lives in the
// GL layer.
#include "engine/render/render_target.h"

#include <algorithm>
#include <limits>

#include "engine/core/error.h"
#include "engine/render/image.h"

namespace engine {

glm::mat4 flip_y_for_target(const glm::mat4& projection) {
    glm::mat4 flip(1.0f);
    flip[1][1] = -1.0f;
    return flip * projection;
}

RenderTarget::RenderTarget(int width, int height) : width_(width), height_(height) {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (width <= 0 || height <= 0 || width > max_size || height > max_size)
        fail("render target size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." +
             std::to_string(max_size));
    color_ = gl::Texture(GL_TEXTURE_2D, "frame colour");
    glTextureStorage2D(color_.id(), 1, GL_RGBA8, width, height);
    depth_ = gl::Texture(GL_TEXTURE_2D, "frame depth");
    glTextureStorage2D(depth_.id(), 1, GL_DEPTH_COMPONENT32F, width, height);
    view_depth_ = gl::Texture(GL_TEXTURE_2D, "frame view depth");
    glTextureStorage2D(view_depth_.id(), 1, GL_R32F, width, height);
    for (GLuint t : {color_.id(), view_depth_.id()}) {
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    framebuffer_ = gl::Framebuffer("frame");
    glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, color_.id(), 0);
    glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT1, view_depth_.id(), 0);
    glNamedFramebufferTexture(framebuffer_.id(), GL_DEPTH_ATTACHMENT, depth_.id(), 0);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(framebuffer_.id(), 2, buffers);
    const GLenum status = glCheckNamedFramebufferStatus(framebuffer_.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        fail("render target framebuffer incomplete: status " + std::to_string(status));
}

void RenderTarget::clear(float r, float g, float b) {
    const float color[] = {r, g, b, 1.0f};
    const float far_depth[] = {std::numeric_limits<float>::infinity(), 0, 0, 0};
    const float depth = 1.0f;
    glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, color);
    glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 1, far_depth);
    glClearNamedFramebufferfv(framebuffer_.id(), GL_DEPTH, 0, &depth);
}

Image RenderTarget::read_color() const {
    Image image{width_, height_,
                std::vector<std::uint8_t>(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4)};
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(color_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(image.rgba.size()),
                      image.rgba.data());
    return image;
}

std::vector<float> RenderTarget::read_view_depth() const {
    std::vector<float> out(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
    glGetTextureImage(view_depth_.id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(out.size() * sizeof(float)),
                      out.data());
    return out;
}

void present_to_window(const RenderTarget& target, glm::ivec2 window_size) {
    present_to_window(target, window_size, {0, 0}, window_size);
}

void present_to_window(const RenderTarget& target, glm::ivec2 window_size, glm::ivec2 origin, glm::ivec2 size) {
    const GLuint source = target.framebuffer().id();
    glNamedFramebufferReadBuffer(source, GL_COLOR_ATTACHMENT0);
    glDisable(GL_SCISSOR_TEST);      // the blit obeys the scissor box a pass may have left set
    glDisable(GL_FRAMEBUFFER_SRGB);  // the target already holds display-space values
    // The window's rows count from the bottom: the rectangle's top is window_size.y − origin.y.
    const GLint top = window_size.y - origin.y, bottom = top - size.y;
    glBlitNamedFramebuffer(source, 0, 0, 0, target.width(), target.height(), origin.x, top, origin.x + size.x, bottom,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, window_size.x, window_size.y);
}

Image read_window(glm::ivec2 window_size) {
    const std::size_t stride = static_cast<std::size_t>(window_size.x) * 4;
    Image image{window_size.x, window_size.y,
                std::vector<std::uint8_t>(stride * static_cast<std::size_t>(window_size.y))};
    std::vector<std::uint8_t> rows(image.rgba.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadnPixels(0, 0, window_size.x, window_size.y, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(rows.size()),
                  rows.data());
    for (int y = 0; y < window_size.y; ++y) {
        const std::size_t from = static_cast<std::size_t>(window_size.y - 1 - y) * stride;
        std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(from), stride,
                    image.rgba.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * stride));
    }
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    return image;
}

}  // namespace engine
