#pragma once
// The drop-in LOD of the splat component ("lod": "auto", docs/lod.md): the cache lookup when a scene
// loads, and the pass that swaps finished bakes in at the start of each frame.
#include <memory>
#include <string>

#include "engine/render/render_pass.h"
#include "splat_lod/splat_component.h"

namespace engine {
class AssetCache;
}

namespace splat_lod {

// For a component whose trained cloud was just loaded: a cloud that already has LOD attributes is
// drawn as it is; else the cached LOD asset of the input's bytes and the settings replaces the cloud,
// or, when there is none, a background bake starts (component.lod_bake). Problems with the cache (no
// cache folder, an unreadable entry) are logged and leave the trained scene drawn.
void start_drop_in_lod(SplatComponent& component, const DropInLodSettings& settings, engine::AssetCache& assets);

// Runs first in every frame: SplatComponent::update_lod() for each splat component of the scene.
class LodSwapPass : public engine::RenderPass {
public:
    std::string name() const override { return "splat.lod_swap"; }
    int order() const override { return engine::pass_order::mesh - 50; }
    void execute(engine::FrameContext& frame) override;
};

}  // namespace splat_lod
