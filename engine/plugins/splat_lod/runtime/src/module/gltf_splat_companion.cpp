// The splats of a glTF file that a "mesh" component names: the engine's mesh loader skips
// KHR_gaussian_splatting primitives (engine::MeshAsset::splat_primitives), and this companion puts a
// splat component with them beside the mesh, on the same node, so one file brings both.
#include "module/gltf_splat_companion.h"

#include <filesystem>
#include <memory>
#include <vector>

#include "engine/assets/asset_cache.h"
#include "engine/assets/mesh_asset.h"
#include "engine/core/error.h"
#include "engine/scene/component_registry.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/splat_component.h"

namespace splat_lod {

void register_gltf_splat_companion(engine::ComponentRegistry& registry, const std::string& owner) {
    registry.add_companion(
        "mesh",
        [](const nlohmann::json& spec, const engine::ComponentLoadContext& ctx) {
            std::vector<std::unique_ptr<engine::Component>> out;
            const auto asset = spec.find("asset");  // the mesh factory has checked it and loaded the mesh
            if (asset == spec.end() || !asset->is_string() || ctx.assets == nullptr) return out;
            const std::filesystem::path path = ctx.resolve(asset->get<std::string>());
            if (ctx.assets->mesh(path)->splat_primitives == 0) return out;
            auto component = std::make_unique<SplatComponent>();
            component->asset = path;
            try {
                component->cloud = ctx.assets->get<SplatCloud>(path, [](const std::filesystem::path& p) {
                    return std::make_shared<const SplatCloud>(read_gltf_splats(p));
                });
            } catch (const engine::Error& e) {
                ctx.error("asset", e.what());
            }
            out.push_back(std::move(component));
            return out;
        },
        owner);
}

}  // namespace splat_lod
