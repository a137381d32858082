#pragma once
// The engine's own component types: "camera", "mesh" and "light".
#include <filesystem>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "engine/scene/component.h"

namespace engine {

class ComponentRegistry;
struct MeshAsset;

struct CameraComponent : Component {
    std::string_view type_name() const override { return "camera"; }
    float fov_y_deg = 50.0f;
    float znear = 0.1f;
    float zfar = 1000.0f;
};

struct MeshComponent : Component {
    std::string_view type_name() const override { return "mesh"; }
    std::optional<Bounds> local_bounds() const override;
    std::filesystem::path asset;
    std::shared_ptr<const MeshAsset> mesh;
    // Drawn after the plugin passes (the late mesh pass, mesh_pass.h) instead of before them: hidden
    // behind every surface they left in the view depth (a splat where its accumulated opacity passes ½)
    // and drawn over what is in front of that. For what is drawn after a plugin's own surfaces: gizmos,
    // markers, effects. A mesh that splats must be seen through stays early (JSON "late", default false).
    bool late = false;
};

// A directional light shines along its node's −Z axis; an ambient light lights from everywhere.
struct LightComponent : Component {
    enum class Kind { directional, ambient };
    std::string_view type_name() const override { return "light"; }
    Kind kind = Kind::directional;
    glm::vec3 color{1.0f};  // linear
    float intensity = 1.0f;
};

void register_builtin_components(ComponentRegistry& registry);

}  // namespace engine
