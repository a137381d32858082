#pragma once
// The "splat" component: a Gaussian splat scene under a node, drawn by the splat_lod pass
// together with every other splat component of the scene (one depth-sorted set).
//   {"type": "splat", "asset": "scene.ply", "sh_degree": 3, "lod": "auto"}
// The node's transform applies; Y-down captures are fixed by rotating the node 180° about X.
// "lod": "auto" is the drop-in LOD (docs/lod.md). The runtime only holds and runs its work (a LodJob);
// what the work is comes from the optional library splat_lod_dropin (splat_lod/dropin/drop_in_lod.h):
// a background bake into the user's cache for a scene that one file serves, or a streamed world built
// from the capture and streamed under the component's node for a large one. Without that library
// "lod": "auto" draws the file as it is and says so once.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include <glm/vec3.hpp>

#include "engine/scene/component.h"
#include "splat_lod/core/splat_cloud.h"

namespace engine {
class AssetCache;
class ComponentRegistry;
class MessageBus;
}  // namespace engine

namespace splat_lod {

struct SplatComponent;

// What a drop-in LOD's work sees of each frame, before any splat is drawn.
struct LodFrame {
    glm::vec3 camera_position{0.0f};  // world space
    float focal_length_px = 0.0f;     // of the output image; 0 when there is no camera (nothing streams)
    std::uint64_t frame_index = 0;
    engine::MessageBus* bus = nullptr;  // the engine's, when there is one (the splat pass's settings are on it)
};

// The work "lod": "auto" does for one component (a bake, an import, a streamer), owned by it.
class LodJob {
public:
    virtual ~LodJob() = default;
    // Once per frame on the thread that renders, before the splat pass: may change the component (its
    // cloud, its node's children). Returns false once the job has nothing more to do (it is then dropped).
    virtual bool update(SplatComponent& component, const LodFrame& frame) = 0;
    // One line for the LOD panel ("importing park.ply: 42 %"); empty when there is nothing to say.
    virtual std::string status() const { return ""; }
};

struct SplatComponent : engine::Component {
    std::string_view type_name() const override { return "splat"; }
    std::optional<engine::Bounds> local_bounds() const override;

    std::filesystem::path asset;
    // May be null: a drop-in LOD that streams the scene as a world draws it through child nodes instead.
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
    // "lod": "auto" while it has work to do; null otherwise (no "lod", nothing left to do).
    std::shared_ptr<LodJob> lod_job;

    // Runs the job's update and drops a finished job; returns true when the cloud changed. The plugin
    // calls it for every splat component at the start of each frame, on the thread that renders, so a
    // frame never sees half a swap.
    bool update_lod(const LodFrame& frame = {});
};

// What "lod": "auto" does with a component whose trained cloud was just loaded (it may set lod_job).
using DropInLod = std::function<void(SplatComponent& component, engine::AssetCache& assets)>;

// Registers the "splat" type (asset path resolved against the scene file, loads cached). `drop_in`
// empty: "lod": "auto" is accepted, draws the file as it is and logs why.
void register_splat_component(engine::ComponentRegistry& registry, const std::string& owner, DropInLod drop_in = {});

}  // namespace splat_lod
