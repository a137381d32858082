#pragma once
// A first-person fly camera: W/S move along the view direction, A/D sideways, E/Q up and down
// in world space, Shift moves faster; with the right mouse button held, mouse motion turns
// (yaw about world +Y, pitch about the camera's right axis). The wheel scales the speed.
// Pure maths on an input snapshot, so it runs and is tested without a window or GL.
#include <glm/glm.hpp>

namespace engine {

// One frame of input, taken from Window by the caller (who also decides whether the UI has it).
struct FlyCameraInput {
    bool forward = false, back = false, left = false, right = false, up = false, down = false;
    bool fast = false;
    bool look = false;            // right mouse button held
    glm::vec2 mouse_delta{0.0f};  // pixels, +x right, +y down
    float scroll = 0.0f;          // wheel steps, + away from the user
};

class FlyCamera {
public:
    FlyCamera() = default;
    // Starts from a camera-to-world matrix (view along −Z, +Y up, as in render/camera.h); roll
    // is dropped because the fly camera keeps the horizon level.
    explicit FlyCamera(const glm::mat4& camera_to_world);
    void look_at(const glm::vec3& eye, const glm::vec3& target);

    void update(const FlyCameraInput& input, float seconds);

    glm::mat4 camera_to_world() const;
    glm::vec3 position() const { return position_; }
    glm::vec3 forward() const;              // unit view direction
    float yaw() const { return yaw_; }      // radians; 0 looks along −Z, positive turns left
    float pitch() const { return pitch_; }  // radians, within ±89°

    float speed = 2.0f;            // world units per second
    float fast_multiplier = 4.0f;  // with Shift
    float turn_rate = 0.003f;      // radians per pixel of mouse motion

private:
    void set_direction(const glm::vec3& direction);

    glm::vec3 position_{0.0f};
    float yaw_ = 0.0f;
    float pitch_ = 0.0f;
};

}  // namespace engine
