#pragma once
// The drop-in LOD: what {"type": "splat", "asset": ..., "lod": "auto"} does (docs/lod.md), in a
// library of its own so that a game that ships baked assets or streamed worlds links neither the
// bake nor the world import. Link splat_lod_dropin and start the plugin with it:
//   engine.plugins().add_static(splat_lod::dropin::make_plugin());
// (the engine's own programs do when built with SPLAT_LOD_DROP_IN, the default).
//
// For a component whose trained cloud was just loaded:
//   - a cloud that already has LOD attributes is drawn as it is;
//   - a scene that one baked file serves (world_advice says nothing) is baked in the background into
//     the user's cache while the trained scene is drawn, and replaces it between two frames; later loads
//     take the asset from the cache;
//   - a capture better served as a streamed world (large, or flat and wide: world_advice says why) is
//     imported in the background into a world folder in the same cache (the import of `splat_world
//     --from`, out of core), while the trained scene is drawn. Then the component streams the world under
//     its own node: a child node "streamed world" placed where the capture was (the import's capture →
//     world map, undone), the chunk streamer driven by the frame's camera (its thresholds are
//     the splat pass's LodSettings on the bus), the world's far layer and props beside the chunks. The trained scene is
//     drawn until the streamer's cut is drawn everywhere (no hole), then released. A later load finds the import done
//     (same capture files, same options) and streams at once.
// Problems (no cache folder, an unreadable entry, a failed bake or import) are logged; the trained scene
// stays drawn and nothing half-made is left in the cache.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "engine/plugin/plugin.h"
#include "splat_lod/bake/bake_setup.h"
#include "splat_lod/bake/capture_shape.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/stream/chunk_streamer.h"
#include "splat_lod/worldgen/world_import.h"

namespace splat_lod::bake {
class BackgroundBake;
}

namespace splat_lod::dropin {

// How "lod": "auto" bakes, imports, streams and where it caches. The bake's defaults are those of
// `splat_bake --capture auto --cameras auto`, the import's those of `splat_world --from`, the
// streaming's the streamer's; tests make them smaller and the cache a temporary folder.
struct DropInLodSettings {
    bake::BakeSetup setup;
    std::filesystem::path cache_folder;  // empty: bake::lod_cache_folder(); worlds go to its worlds/
    // Called on the work's thread with its progress (a bake's stages, an import's "import: chunks" …);
    // may throw to fail the work (for tests).
    std::function<void(const std::string& stage, double fraction)> observer;
    // Why a trained scene is better served as a streamed world than by one baked file ("" when one file
    // is fine). Tests give their own.
    std::function<std::string(const SplatCloud&)> world_advice = bake::streamed_world_advice;
    // The import of such a scene: `capture`, `output` and `progress` are set per scene.
    world::ImportOptions import;
    // Its streaming: budgets, fades, groups. The thresholds follow the splat pass's LodSettings on the
    // engine's bus (chunk_streamer.h) and the SH degree is capped by the component's.
    world::StreamerSettings streaming;
};

// The drop-in LOD for register_splat_component() / splat_lod::make_plugin(DropInLod).
DropInLod make_drop_in(DropInLodSettings settings = {});

// The splat_lod plugin with make_drop_in()'s defaults.
std::unique_ptr<engine::Plugin> make_plugin();

// The folder "lod": "auto" imports `capture` into: <cache>/worlds/<name>-<CRC-32 of its absolute path>, the
// name being the file's stem, or its folder's name for a streamed SOG (lod-meta.json) or a SOG's meta.json.
std::filesystem::path world_cache_folder(const std::filesystem::path& cache_folder,
                                         const std::filesystem::path& capture);

// For tools and tests: the component's background bake, or null when its drop-in LOD is not a bake.
std::shared_ptr<bake::BackgroundBake> background_bake(const SplatComponent& component);

// For tools and tests: where a component's drop-in world stands.
struct WorldStatus {
    // none: no world (a failed import or world ends the job, which logs why); holding: streamed, the
    // trained scene still drawn until the cut is drawn everywhere.
    enum class State { none, importing, holding, streaming };
    State state = State::none;
    std::filesystem::path folder;
    world::ChunkStreamer* streamer = nullptr;  // holding and streaming
};
WorldStatus world_status(const SplatComponent& component);
// Blocks until the component's import has ended (the world's update still has to run to stream it);
// returns false when `seconds` passed first, true at once when it has no import.
bool wait_for_import(const SplatComponent& component, double seconds);

}  // namespace splat_lod::dropin
