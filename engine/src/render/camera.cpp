#include "engine/render/camera.h"

#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.h"
#include "engine/scene/transform.h"

namespace engine {

namespace {

glm::ivec2 whole_size(const CameraView& c) {
    return c.full_size.x > 0 ? c.full_size : glm::ivec2(c.width, c.height);
}

}  // namespace

float CameraView::focal_length() const {
    return 0.5f * static_cast<float>(whole_size(*this).y) / std::tan(0.5f * fov_y);
}

glm::vec2 CameraView::principal_point() const {
    return 0.5f * glm::vec2(whole_size(*this)) - glm::vec2(tile_origin);
}

float CameraView::aspect() const {
    const glm::ivec2 size = whole_size(*this);
    return static_cast<float>(size.x) / static_cast<float>(size.y);
}

glm::vec3 CameraView::project_to_pixel(const glm::vec3& world) const {
    const glm::vec3 v = glm::vec3(view * glm::vec4(world, 1.0f));
    const float z = -v.z;
    const float f = focal_length();
    const glm::vec2 c = principal_point();
    return {c.x + f * v.x / z, c.y - f * v.y / z, z};
}

CameraView make_camera(const glm::mat4& camera_to_world, float fov_y_radians, int width, int height, float znear,
                       float zfar) {
    if (width <= 0 || height <= 0)
        fail("camera: image size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
    if (!(fov_y_radians > 0.0f && fov_y_radians < 3.14f))
        fail("camera: vertical field of view must be in (0, 180) degrees");
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

CameraView make_look_at_camera(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fov_y_radians,
                               int width, int height, float znear, float zfar) {
    if (glm::length(target - eye) <= 0.0f) fail("camera: eye and target coincide");
    Transform t;
    t.translation = eye;
    t.rotation = Transform::look_rotation(eye, target, up);
    return make_camera(t.matrix(), fov_y_radians, width, height, znear, zfar);
}

CameraView tile_view(const CameraView& whole, glm::ivec2 origin, glm::ivec2 size) {
    const glm::ivec2 full = whole_size(whole);
    const glm::ivec2 first = whole.tile_origin + origin, end = first + size;
    if (size.x <= 0 || size.y <= 0 || origin.x < 0 || origin.y < 0 || origin.x + size.x > whole.width ||
        origin.y + size.y > whole.height)
        fail("camera: tile " + std::to_string(size.x) + "x" + std::to_string(size.y) + " at (" +
             std::to_string(origin.x) + ", " + std::to_string(origin.y) + ") is not inside the " +
             std::to_string(whole.width) + "x" + std::to_string(whole.height) + " image");
    CameraView c = whole;
    c.width = size.x;
    c.height = size.y;
    c.full_size = full;
    c.tile_origin = first;
    // The tile's edges as x/z and y/z in view space (image rows grow downwards, view Y upwards).
    const float f = whole.focal_length();
    const glm::vec2 centre = 0.5f * glm::vec2(full);
    const float left = (static_cast<float>(first.x) - centre.x) / f, right = (static_cast<float>(end.x) - centre.x) / f;
    const float top = (centre.y - static_cast<float>(first.y)) / f, bottom = (centre.y - static_cast<float>(end.y)) / f;
    c.projection = glm::frustum(left * c.znear, right * c.znear, bottom * c.znear, top * c.znear, c.znear, c.zfar);
    return c;
}

StereoEyes stereo_eyes(const CameraView& centre, float ipd) {
    if (!(ipd >= 0.0f) || !std::isfinite(ipd)) fail("stereo: the eye separation must be a finite distance >= 0");
    const glm::mat4 to_world = glm::inverse(centre.view);
    const glm::vec3 right = glm::normalize(glm::vec3(to_world[0]));
    StereoEyes eyes{centre, centre};
    for (auto [eye, side] : {std::pair{&eyes.left, -0.5f}, std::pair{&eyes.right, 0.5f}}) {
        glm::mat4 m = to_world;
        m[3] = glm::vec4(centre.position + side * ipd * right, 1.0f);
        eye->view = glm::inverse(m);
        eye->position = glm::vec3(m[3]);
        eye->selection_view = centre.selection_view.value_or(centre.view);
    }
    return eyes;
}

}  // namespace engine
