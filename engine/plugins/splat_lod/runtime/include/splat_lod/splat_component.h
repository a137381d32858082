#pragma once
// The "splat" component: a Gaussian splat scene under a node, drawn by the splat_lod pass
// together with every other splat component of the scene (one depth-sorted set).
//   {"type": "splat", "asset": "scene.ply", "sh_degree": 3}
// The node's transform applies; Y-down captures are fixed by rotating the node 180° about X.
#include <filesystem>
#include <memory>

#include "engine/scene/component.h"
#include "splat_lod/core/splat_cloud.h"

namespace engine {
class ComponentRegistry;
}

namespace splat_lod {

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
};

// Registers the "splat" type (asset path resolved against the scene file, loads cached).
void register_splat_component(engine::ComponentRegistry& registry, const std::string& owner);

}  // namespace splat_lod
