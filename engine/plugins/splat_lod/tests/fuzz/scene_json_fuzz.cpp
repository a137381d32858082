// Scene files (engine/scene/scene_loader.h) through load_scene_text, with the engine's built-in
// component types and splat_lod's "splat" registered, as the engine's tools have them. The scene
// is named <sandbox>/scene.json; its assets resolve against that folder, where triangle.gltf,
// cloud.ply and cloud.splat exist (fuzz_support.h). An asset path that leaves the sandbox is
// refused before the real factory runs (as an engine::Error), so the fuzzer never reads other
// files; everything inside the sandbox goes through the real factories and loaders.
// Contract: a scene whose transforms and components are finite and valid, or engine::Error
// "<file>: <key path>: <problem>".
#include <cmath>
#include <utility>

#include "engine/assets/asset_cache.h"
#include "engine/core/error.h"
#include "engine/scene/builtin_components.h"
#include "engine/scene/component_registry.h"
#include "engine/scene/json_fields.h"
#include "engine/scene/scene_loader.h"
#include "splat_fuzz_support.h"
#include "splat_lod/dropin/drop_in_lod.h"
#include "splat_lod/splat_component.h"

namespace {

using splat_fuzz::finite;
using splat_fuzz::require;

// The real factories behind a guard that keeps "asset" paths inside the sandbox.
const engine::ComponentRegistry& sandboxed_registry() {
    static const engine::ComponentRegistry real = [] {
        engine::ComponentRegistry registry;
        engine::register_builtin_components(registry);
        splat_lod::dropin::DropInLodSettings lod;  // "lod": "auto" caches inside the sandbox too
        lod.cache_folder = splat_fuzz::sandbox_dir() / "lod_cache";
        splat_lod::register_splat_component(registry, "splat_lod", splat_lod::dropin::make_drop_in(std::move(lod)));
        return registry;
    }();
    static const engine::ComponentRegistry guarded = [] {
        engine::ComponentRegistry registry;
        for (const auto& type : real.types())
            registry.add(type, [type](const nlohmann::json& spec, const engine::ComponentLoadContext& ctx) {
                const auto asset = spec.find("asset");
                if (asset != spec.end() && asset->is_string() &&
                    !splat_fuzz::inside_sandbox(ctx.resolve(asset->get<std::string>())))
                    ctx.error("asset", "outside the fuzz sandbox (not loaded)");
                return real.create(type, spec, ctx);
            });
        return registry;
    }();
    return guarded;
}

void check_component(const engine::Component& component) {
    if (const auto* camera = dynamic_cast<const engine::CameraComponent*>(&component)) {
        require(camera->fov_y_deg > 0.0f && camera->fov_y_deg < 179.0f, "camera fov in (0, 179)");
        require(camera->znear > 0.0f && std::isfinite(camera->zfar) && camera->zfar > camera->znear,
                "camera 0 < znear < zfar, finite");
    } else if (const auto* light = dynamic_cast<const engine::LightComponent*>(&component)) {
        require(finite(light->color) && std::isfinite(light->intensity) && light->intensity >= 0.0f,
                "light colour and intensity finite, intensity >= 0");
    } else if (const auto* mesh = dynamic_cast<const engine::MeshComponent*>(&component)) {
        require(mesh->mesh != nullptr, "a mesh component holds its mesh");
    } else if (const auto* splat = dynamic_cast<const splat_lod::SplatComponent*>(&component)) {
        require(splat->cloud != nullptr, "a splat component holds its cloud");
        require(splat->sh_degree_cap >= 0 && splat->sh_degree_cap <= splat_lod::kMaxShDegree, "sh_degree 0..3");
    }
}

void check_scene(const engine::Scene& scene) {
    require(finite(scene.background), "background is finite");
    scene.root().visit([](const engine::Node& node) {
        const engine::Transform& t = node.transform();
        const glm::vec4 q(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z);
        require(finite(t.translation) && finite(t.scale), "node '" + node.name() + "': finite translation and scale");
        require(finite(q) && std::fabs(glm::length(q) - 1.0f) < 1e-3f, "node '" + node.name() + "': unit rotation");
        for (const auto& component : node.components()) check_component(*component);
    });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    splat_fuzz::quiet_engine_log();
    splat_fuzz::write_sandbox_assets();
    const auto path = splat_fuzz::sandbox_dir() / "scene.json";
    engine::AssetCache assets;  // per input, so that no run depends on an earlier one
    std::unique_ptr<engine::Scene> scene;
    try {
        scene = engine::load_scene_text(splat_fuzz::text_of(data, size), path, sandboxed_registry(), assets);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, path.string());
        return 0;
    }
    check_scene(*scene);
    return 0;
}
