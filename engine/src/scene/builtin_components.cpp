#include "engine/scene/builtin_components.h"

#include "engine/assets/asset_cache.h"
#include "engine/assets/mesh_asset.h"
#include "engine/core/error.h"
#include "engine/scene/component_registry.h"
#include "engine/scene/json_fields.h"

namespace engine {
namespace {

namespace jf = json_fields;

std::unique_ptr<Component> make_camera(const nlohmann::json& spec, const ComponentLoadContext& ctx) {
    jf::only_keys(spec, {"type", "fov_y_deg", "znear", "zfar"}, ctx);
    auto camera = std::make_unique<CameraComponent>();
    camera->fov_y_deg = jf::number(spec, "fov_y_deg", camera->fov_y_deg, ctx);
    camera->znear = jf::number(spec, "znear", camera->znear, ctx);
    camera->zfar = jf::number(spec, "zfar", camera->zfar, ctx);
    if (!(camera->fov_y_deg > 0.0f && camera->fov_y_deg < 179.0f)) ctx.error("fov_y_deg", "must be in (0, 179)");
    if (!(camera->znear > 0.0f)) ctx.error("znear", "must be positive");
    if (!(camera->zfar > camera->znear)) ctx.error("zfar", "must be greater than znear");
    return camera;
}

std::unique_ptr<Component> make_mesh(const nlohmann::json& spec, const ComponentLoadContext& ctx) {
    jf::only_keys(spec, {"type", "asset", "late"}, ctx);
    auto mesh = std::make_unique<MeshComponent>();
    mesh->asset = ctx.resolve(jf::required_string(spec, "asset", ctx));
    mesh->late = jf::boolean(spec, "late", false, ctx);
    if (ctx.assets == nullptr) fail("engine::make_mesh(): no asset cache");
    try {
        mesh->mesh = ctx.assets->mesh(mesh->asset);
    } catch (const Error& e) {
        ctx.error("asset", e.what());
    }
    return mesh;
}

std::unique_ptr<Component> make_light(const nlohmann::json& spec, const ComponentLoadContext& ctx) {
    jf::only_keys(spec, {"type", "kind", "color", "intensity"}, ctx);
    auto light = std::make_unique<LightComponent>();
    const std::string kind = jf::string(spec, "kind", "directional", ctx);
    if (kind == "directional")
        light->kind = LightComponent::Kind::directional;
    else if (kind == "ambient")
        light->kind = LightComponent::Kind::ambient;
    else
        ctx.error("kind", "unknown light kind '" + kind + "' (known: directional, ambient)");
    light->color = jf::vec3(spec, "color", light->color, ctx);
    light->intensity = jf::number(spec, "intensity", light->intensity, ctx);
    if (light->intensity < 0.0f) ctx.error("intensity", "must not be negative");
    return light;
}

}  // namespace

std::optional<Bounds> MeshComponent::local_bounds() const {
    if (!mesh) return std::nullopt;
    return Bounds{mesh->bounds_min, mesh->bounds_max};
}

void register_builtin_components(ComponentRegistry& registry) {
    registry.add("camera", make_camera);
    registry.add("mesh", make_mesh);
    registry.add("light", make_light);
}

}  // namespace engine
