#include "splat_lod/splat_component.h"

#include <algorithm>
#include <limits>

#include "engine/assets/asset_cache.h"
#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/scene/component_registry.h"
#include "engine/scene/json_fields.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod {

std::optional<engine::Bounds> SplatComponent::local_bounds() const {
    if (!cloud || cloud->empty()) return std::nullopt;
    engine::Bounds b{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
    for (const auto& p : cloud->positions) {
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
    }
    return b;
}

void register_splat_component(engine::ComponentRegistry& registry, const std::string& owner, DropInLod drop_in) {
    registry.add(
        "splat",
        [drop_in = std::move(drop_in)](const nlohmann::json& spec,
                                       const engine::ComponentLoadContext& ctx) -> std::unique_ptr<engine::Component> {
            namespace jf = engine::json_fields;
            jf::only_keys(spec, {"type", "asset", "sh_degree", "lod"}, ctx);
            auto component = std::make_unique<SplatComponent>();
            component->asset = ctx.resolve(jf::required_string(spec, "asset", ctx));
            component->sh_degree_cap = jf::integer(spec, "sh_degree", kMaxShDegree, ctx);
            if (component->sh_degree_cap < 0 || component->sh_degree_cap > kMaxShDegree)
                ctx.error("sh_degree", "must be 0..3");
            const std::string lod_mode = jf::string(spec, "lod", "", ctx);
            if (spec.contains("lod") && lod_mode != "auto")
                ctx.error("lod", "'" + lod_mode +
                                     "' is not a LOD mode (known: auto; leave \"lod\" out to draw the file as it is)");
            if (ctx.assets == nullptr) engine::fail("splat_lod: no asset cache");
            try {
                component->cloud = ctx.assets->get<SplatCloud>(component->asset, [](const std::filesystem::path& p) {
                    return std::make_shared<const SplatCloud>(load_splat_file(p));
                });
            } catch (const engine::Error& e) {
                ctx.error("asset", e.what());
            }
            if (lod_mode != "auto") return component;
            if (drop_in)
                drop_in(*component, *ctx.assets);
            else
                engine::log_warning(
                    "splat_lod: " + component->asset.filename().string() +
                    ": \"lod\": \"auto\" needs the drop-in LOD (the splat_lod_dropin library, "
                    "splat_lod/dropin/drop_in_lod.h), which this program was built without; drawn as it is");
            return component;
        },
        owner);
}

}  // namespace splat_lod
