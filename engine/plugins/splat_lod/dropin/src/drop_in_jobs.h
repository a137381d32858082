#pragma once
// The two kinds of work of the drop-in LOD (drop_in_lod.h): a background bake into the cache, and a
// capture imported as a world in the background and then streamed under the component's node.
#include <memory>
#include <string>

#include "splat_lod/dropin/drop_in_lod.h"

namespace engine {
class AssetCache;
}

namespace splat_lod::dropin {

// settings.cache_folder, else the user's cache (bake::lod_cache_folder(), which throws when there is none).
std::filesystem::path cache_root(const DropInLodSettings& settings);

// Bakes `component`'s trained cloud in the background (cache hit: swaps the cached asset in at once).
void start_bake(SplatComponent& component, const DropInLodSettings& settings, engine::AssetCache& assets);

// Imports `component`'s capture as a world in the background (`why`: what world_advice said), then
// streams it.
void start_world(SplatComponent& component, const DropInLodSettings& settings, engine::AssetCache& assets,
                 const std::string& why);

}  // namespace splat_lod::dropin
