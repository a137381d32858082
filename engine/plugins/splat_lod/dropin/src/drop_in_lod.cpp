#include "splat_lod/dropin/drop_in_lod.h"

#include <utility>

#include "drop_in_jobs.h"
#include "splat_lod/bake/lod_cache.h"
#include "splat_lod/splat_lod_plugin.h"

namespace splat_lod::dropin {

std::filesystem::path cache_root(const DropInLodSettings& settings) {
    return settings.cache_folder.empty() ? bake::lod_cache_folder() : settings.cache_folder;
}

DropInLod make_drop_in(DropInLodSettings settings) {
    return [settings = std::move(settings)](SplatComponent& component, engine::AssetCache& assets) {
        if (!component.cloud || component.cloud->has_lod_attributes()) return;
        if (const std::string why = settings.world_advice ? settings.world_advice(*component.cloud) : ""; !why.empty())
            start_world(component, settings, assets, why);
        else
            start_bake(component, settings, assets);
    };
}

std::unique_ptr<engine::Plugin> make_plugin() {
    return splat_lod::make_plugin(make_drop_in());
}

}  // namespace splat_lod::dropin
