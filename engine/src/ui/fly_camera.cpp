#include "engine/ui/fly_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace engine {
namespace {

constexpr glm::vec3 world_up{0.0f, 1.0f, 0.0f};
// Short of ±90° so that the right vector cross(forward, up) never degenerates.
constexpr float max_pitch = 89.0f * 3.14159265358979f / 180.0f;

}  // namespace

FlyCamera::FlyCamera(const glm::mat4& camera_to_world) {
    position_ = glm::vec3(camera_to_world[3]);
    glm::vec3 direction = -glm::vec3(camera_to_world[2]);
    const glm::vec3 horizontal(direction.x, 0.0f, direction.z);
    if (glm::length(horizontal) < 1e-6f) {
        // Looking straight up or down: the heading is where the camera's up vector points.
        const glm::vec3 up = glm::vec3(camera_to_world[1]);
        const glm::vec3 heading = direction.y < 0.0f ? up : -up;
        direction = glm::normalize(glm::vec3(heading.x, 0.0f, heading.z)) * 1e-3f + direction;
    }
    set_direction(direction);
}

void FlyCamera::look_at(const glm::vec3& eye, const glm::vec3& target) {
    position_ = eye;
    if (glm::length(target - eye) > 0.0f) set_direction(target - eye);
}

void FlyCamera::set_direction(const glm::vec3& direction) {
    const glm::vec3 d = glm::normalize(direction);
    yaw_ = std::atan2(-d.x, -d.z);
    pitch_ = std::clamp(std::asin(std::clamp(d.y, -1.0f, 1.0f)), -max_pitch, max_pitch);
}

glm::vec3 FlyCamera::forward() const {
    return {-std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), -std::cos(yaw_) * std::cos(pitch_)};
}

void FlyCamera::update(const FlyCameraInput& input, float seconds) {
    if (input.scroll != 0.0f) speed = std::clamp(speed * std::pow(1.2f, input.scroll), 1e-3f, 1e4f);
    if (input.look) {
        // Mouse right turns right (yaw decreases), mouse down looks down.
        yaw_ -= input.mouse_delta.x * turn_rate;
        pitch_ = std::clamp(pitch_ - input.mouse_delta.y * turn_rate, -max_pitch, max_pitch);
        yaw_ = std::remainder(yaw_, 2.0f * glm::pi<float>());
    }
    const glm::vec3 ahead = forward();
    const glm::vec3 right = glm::normalize(glm::cross(ahead, world_up));
    glm::vec3 move(0.0f);
    if (input.forward) move += ahead;
    if (input.back) move -= ahead;
    if (input.right) move += right;
    if (input.left) move -= right;
    if (input.up) move += world_up;
    if (input.down) move -= world_up;
    if (glm::length(move) == 0.0f) return;
    const float rate = speed * (input.fast ? fast_multiplier : 1.0f);
    position_ += glm::normalize(move) * rate * seconds;
}

glm::mat4 FlyCamera::camera_to_world() const {
    const glm::vec3 ahead = forward();
    const glm::vec3 right = glm::normalize(glm::cross(ahead, world_up));
    const glm::vec3 up = glm::cross(right, ahead);
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(right, 0.0f);
    m[1] = glm::vec4(up, 0.0f);
    m[2] = glm::vec4(-ahead, 0.0f);
    m[3] = glm::vec4(position_, 1.0f);
    return m;
}

}  // namespace engine
