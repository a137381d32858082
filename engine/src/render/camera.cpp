#include "engine/render/camera.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.h"
#include "engine/scene/transform.h"

namespace engine {

float CameraView::focal_length() const { return 0.5f * static_cast<float>(height) / std::tan(0.5f * fov_y); }

glm::vec2 CameraView::principal_point() const { return {0.5f * static_cast<float>(width), 0.5f * static_cast<float>(height)}; }

glm::vec3 CameraView::project_to_pixel(const glm::vec3& world) const {
    const glm::vec3 v = glm::vec3(view * glm::vec4(world, 1.0f));
    const float z = -v.z;
    const float f = focal_length();
    const glm::vec2 c = principal_point();
    return {c.x + f * v.x / z, c.y - f * v.y / z, z};
}

CameraView make_camera(const glm::mat4& camera_to_world, float fov_y_radians, int width, int height, float znear,
                       float zfar) {
    if (width <= 0 || height <= 0) fail("camera: image size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
    if (!(fov_y_radians > 0.0f && fov_y_radians < 3.14f)) fail("camera: vertical field of view must be in (0, 180) degrees");
    if (!(znear > 0.0f && zfar > znear)) fail("camera: need 0 < znear < zfar");
    CameraView c;
    c.view = glm::inverse(camera_to_world);
    c.position = glm::vec3(camera_to_world[3]);
    c.fov_y = fov_y_radians;
    c.znear = znear;
    c.zfar = zfar;
    c.width = width;
    c.height = height;
    c.projection = glm::perspective(fov_y_radians, static_cast<float>(width) / static_cast<float>(height), znear, zfar);
    return c;
}

CameraView make_look_at_camera(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up,
                               float fov_y_radians, int width, int height, float znear, float zfar) {
    if (glm::length(target - eye) <= 0.0f) fail("camera: eye and target coincide");
    Transform t;
    t.translation = eye;
    t.rotation = Transform::look_rotation(eye, target, up);
    return make_camera(t.matrix(), fov_y_radians, width, height, znear, zfar);
}

}  // namespace engine
