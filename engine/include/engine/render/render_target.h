#pragma once
// The offscreen frame every pass draws into: display-space colour (RGBA8, sRGB-encoded values),
// a depth buffer, and the view-space depth z = −z_view of the nearest mesh surface per pixel
// (R32F, +inf where no mesh), which splat passes read to stop at meshes; a plugin pass that draws
// surfaces of its own leaves there the nearer of the two per pixel (the splat pass: where its splats'
// accumulated opacity first exceeds ½), so the passes after it (post, UI) see every surface's depth.
// Texel row 0 is the TOP image row (camera.h's image space), so compute passes index texels by
// pixel (i, j) directly; raster passes flip Y in their projection (flip_y_for_target()) and
// presenting to a window flips once in the blit.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gl/objects.h"

namespace engine {

struct Image;

// Clip-space Y flip that makes rasterised row 0 the top row of a RenderTarget. Triangles'
// winding flips with it: draw with glFrontFace(GL_CW) for counter-clockwise front faces.
glm::mat4 flip_y_for_target(const glm::mat4& projection);

class RenderTarget {
public:
    RenderTarget(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }

    const gl::Texture& color() const { return color_; }
    const gl::Texture& depth() const { return depth_; }
    const gl::Texture& view_depth() const { return view_depth_; }
    const gl::Framebuffer& framebuffer() const { return framebuffer_; }

    // Clears colour to `background` (display space, alpha 1), depth to far, view depth to +inf.
    void clear(float r, float g, float b);
    // Reads the colour back (top row first), blocking; for tools, tests and screenshots.
    Image read_color() const;
    std::vector<float> read_view_depth() const;  // top row first

private:
    int width_, height_;
    gl::Texture color_{gl::NoCreate}, depth_{gl::NoCreate}, view_depth_{gl::NoCreate};
    gl::Framebuffer framebuffer_{gl::NoCreate};
};

// Presenting to a window: copies the target's colour into the default framebuffer (the window's back
// buffer, `window_size` pixels), flipping Y once (the target's row 0 is the top, the window's the
// bottom), and leaves the default framebuffer bound with that viewport for an overlay.
void present_to_window(const RenderTarget& target, glm::ivec2 window_size);
// The same into the window's rectangle of `size` pixels at `origin` (top-left origin), e.g. one eye of a
// stereo pair side by side.
void present_to_window(const RenderTarget& target, glm::ivec2 window_size, glm::ivec2 origin, glm::ivec2 size);
// The window's back buffer (before the swap, when its contents are defined), top row first, opaque:
// the window's alpha is whatever an overlay's blending left, and a screenshot is opaque.
Image read_window(glm::ivec2 window_size);

}  // namespace engine
