#pragma once
// The one statement of the camera and pixel conventions used by every pass, the CPU reference,
// the tools and the tests:
// - view space: right-handed, the camera looks down −Z, +Y is up; depth z = −z_view > 0;
// - image space: origin at the top-left corner, rows top to bottom, pixel (i, j) has its centre
//   at (i + 0.5, j + 0.5); a point displaced along the camera's up vector appears higher;
// - square pixels: fy = fx = (H / 2) / tan(fov_y / 2), principal point at the image centre.
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

    float focal_length() const;          // fx = fy in pixels
    glm::vec2 principal_point() const;   // (W/2, H/2)
    // Image coordinates of a world point (top-left origin) and its depth z = −z_view.
    glm::vec3 project_to_pixel(const glm::vec3& world) const;
};

CameraView make_camera(const glm::mat4& camera_to_world, float fov_y_radians, int width, int height, float znear,
                       float zfar);
CameraView make_look_at_camera(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up,
                               float fov_y_radians, int width, int height, float znear, float zfar);

}  // namespace engine
