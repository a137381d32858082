#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace engine {

// Translation, rotation, scale; the local matrix is T·R·S (glTF's convention).
struct Transform {
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // (w, x, y, z)
    glm::vec3 scale{1.0f};

    glm::mat4 matrix() const;
    // Rotation that points the node's −Z axis from `eye` to `target` with `up` as up.
    static glm::quat look_rotation(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up);
};

}  // namespace engine
