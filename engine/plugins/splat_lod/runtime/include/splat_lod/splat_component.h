#pragma once
// The "splat" component: a Gaussian splat scene under a node, drawn by the splat_lod pass
// together with every other splat component of the scene (one depth-sorted set).
//   {"type": "splat", "asset": "scene.ply", "sh_degree": 3, "lod": "auto"}
// The node's transform applies; Y-down captures are fixed by rotating the node 180° about X.
// "lod": "auto" is the drop-in LOD (docs/lod.md): the trained scene is drawn at once while its LOD
// asset is baked in the background into the user's cache, and replaces it between two frames; later
// loads take the asset from the cache.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "engine/scene/component.h"
#include "splat_lod/bake/bake_setup.h"
#include "splat_lod/bake/capture_shape.h"
#include "splat_lod/core/splat_cloud.h"

namespace engine {
class ComponentRegistry;
}

namespace splat_lod {

namespace bake {
class BackgroundBake;
}

struct SplatComponent : engine::Component {
    std::string_view type_name() const override { return "splat"; }
    std::optional<engine::Bounds> local_bounds() const override;

    std::filesystem::path asset;
    std::shared_ptr<const SplatCloud> cloud;
    int sh_degree_cap = kMaxShDegree;  // 0..3; the cloud's own degree limits it further
    // False: kept on the GPU but not drawn (its clusters are dropped before any per-Gaussian work),
    // so that a streamer can switch between coarse and fine parts of a world without re-uploading.
    bool visible = true;
    // Multiplies the opacity of every Gaussian, clamped to [0, 1]: a streamer fades a part in as it
    // arrives and out as what replaces it takes over (chunk_streamer.h, "fades").
    float opacity = 1.0f;
    // True: `opacity` is instead the fraction of the Gaussians drawn, each at its full opacity (a fixed
    // pseudo-random subset while the component stays resident; deterministic). A cross-fade between two
    // parts then draws about as many Gaussians as the larger of them, not both; the streamer's parts use it.
    bool dissolve = false;
    // "lod": "auto" while its bake runs; null otherwise (no "lod", a cache hit, or the bake ended).
    std::shared_ptr<bake::BackgroundBake> lod_bake;

    // Takes a finished bake's cloud in place of the trained one and returns true; a failed or cancelled
    // bake is dropped (the trained scene stays). The plugin calls it for every splat component at the
    // start of each frame, on the thread that renders, so a frame never sees half a swap.
    bool update_lod();
};

// How "lod": "auto" bakes and where it caches. The defaults are those of
// `splat_bake --capture auto --cameras auto` and splat_lod::bake::lod_cache_folder(); tests make the
// bake shorter and the cache a temporary folder.
struct DropInLodSettings {
    bake::BakeSetup setup;
    std::filesystem::path cache_folder;  // empty: bake::lod_cache_folder()
    // Called on the bake's thread with its progress; may throw to fail the bake (for tests).
    std::function<void(const std::string& stage, double fraction)> observer;
    // Why a trained scene is better served as a streamed world than by one baked file ("" when one file
    // is fine): such a scene is drawn as trained and not baked (docs/lod.md, "Drop-in LOD"). Tests give
    // their own.
    std::function<std::string(const SplatCloud&)> world_advice = bake::streamed_world_advice;
};

// Registers the "splat" type (asset path resolved against the scene file, loads cached).
void register_splat_component(engine::ComponentRegistry& registry, const std::string& owner,
                              DropInLodSettings lod = {});

}  // namespace splat_lod
