#pragma once
// The one statement of the camera and pixel conventions used by every pass, the CPU reference,
// the tools and the tests:
// - view space: right-handed, the camera looks down −Z, +Y is up; depth z = −z_view > 0;
// - image space: origin at the top-left corner, rows top to bottom, pixel (i, j) has its centre
//   at (i + 0.5, j + 0.5); a point displaced along the camera's up vector appears higher;
// - square pixels: fy = fx = (H / 2) / tan(fov_y / 2), principal point at the image centre;
// - a tile (tile_view()) is a window of a larger image: W, H, the centre and fov_y are then that
//   image's, so a tiled render puts every pixel where the whole image has it.
#include <optional>

#include <glm/glm.hpp>

namespace engine {

struct CameraView {
    glm::mat4 view{1.0f};        // world → view
    glm::mat4 projection{1.0f};  // view → clip (OpenGL, depth −1..1)
    glm::vec3 position{0.0f};    // camera centre in world space
    float fov_y = 0.8f;          // radians
    float znear = 0.1f;
    float zfar = 1000.0f;
    int width = 1;
    int height = 1;
    // A tile of a larger image (tile_view()): this view draws its pixels [tile_origin, tile_origin +
    // (width, height)); full_size (0, 0): the view is the whole image.
    glm::ivec2 full_size{0};
    glm::ivec2 tile_origin{0};
    // The view that chooses what is drawn where a pass selects by how large things look (the splat
    // pass's level of detail): none for this view itself. A stereo pair's eyes share their centre's
    // (stereo_eyes()), so that both draw the same selection.
    std::optional<glm::mat4> selection_view;

    float focal_length() const;         // fx = fy in pixels (of the whole image's height)
    glm::vec2 principal_point() const;  // (W/2, H/2) of the whole image, in this view's pixels
    float aspect() const;               // the whole image's W / H
    // Image coordinates of a world point (top-left origin) and its depth z = −z_view.
    glm::vec3 project_to_pixel(const glm::vec3& world) const;
};

CameraView make_camera(const glm::mat4& camera_to_world, float fov_y_radians, int width, int height, float znear,
                       float zfar);
CameraView make_look_at_camera(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fov_y_radians,
                               int width, int height, float znear, float zfar);
// The pixels [origin, origin + size) of `whole` (itself possibly a tile) as a view of their own:
// same pose, field of view and focal length, an off-centre projection. Throws engine::Error when
// the window is empty or leaves the image.
CameraView tile_view(const CameraView& whole, glm::ivec2 origin, glm::ivec2 size);

// A stereo pair for `centre`: two views `ipd` apart along its right axis (left first), looking the same
// way with the same lens and size (parallel axes), whose selection is the centre's (selection_view).
// Throws engine::Error for an ipd that is negative or not finite.
struct StereoEyes {
    CameraView left, right;
};
StereoEyes stereo_eyes(const CameraView& centre, float ipd);

}  // namespace engine
