#include "engine/render/scene_camera.h"

#include <algorithm>

#include "engine/core/error.h"
#include "engine/scene/builtin_components.h"
#include "engine/scene/scene.h"

namespace engine {

std::optional<CameraView> scene_camera(const Scene& scene, const std::string& node_name, int width, int height) {
    for (const auto* camera : scene.components<CameraComponent>()) {
        if (!node_name.empty() && camera->node()->name() != node_name) continue;
        glm::mat4 world = camera->node()->world_matrix();
        // A camera ignores scale: keep only rotation and translation.
        for (int axis = 0; axis < 3; ++axis) world[axis] = glm::vec4(glm::normalize(glm::vec3(world[axis])), 0.0f);
        return make_camera(world, glm::radians(camera->fov_y_deg), width, height, camera->znear, camera->zfar);
    }
    if (!node_name.empty()) fail("scene has no camera on a node named '" + node_name + "'");
    return std::nullopt;
}

CameraView framing_camera(const Scene& scene, int width, int height, float fov_y_radians) {
    const auto bounds = scene.world_bounds();
    const glm::vec3 lo = bounds ? bounds->min : glm::vec3(-1.0f);
    const glm::vec3 hi = bounds ? bounds->max : glm::vec3(1.0f);
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const float half_fov = 0.5f * std::min(fov_y_radians, 2.0f * std::atan(std::tan(0.5f * fov_y_radians) * aspect));
    const float distance = radius / std::sin(half_fov) * 1.05f;
    const glm::vec3 direction = glm::normalize(glm::vec3(0.55f, 0.45f, 1.0f));
    return make_look_at_camera(centre + direction * distance, centre, glm::vec3(0, 1, 0), fov_y_radians, width, height,
                               std::max(distance - radius * 1.5f, distance * 1e-3f), distance + radius * 2.0f);
}

}  // namespace engine
