#pragma once
// Choosing the camera a scene is viewed from: a named or first camera component, or a view that
// frames the scene's bounds.
#include <optional>
#include <string>

#include "engine/render/camera.h"

namespace engine {

class Scene;

// The camera component on the node called `node_name` (any camera when empty), or nullopt when
// the scene has none. Throws when a named node has no camera.
std::optional<CameraView> scene_camera(const Scene& scene, const std::string& node_name, int width, int height);

// A three-quarter view from above-front that fits the scene's world bounds.
CameraView framing_camera(const Scene& scene, int width, int height, float fov_y_radians);

}  // namespace engine
