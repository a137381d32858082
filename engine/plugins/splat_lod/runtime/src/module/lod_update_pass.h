#pragma once
// The pass that runs the drop-in LOD's work ("lod": "auto", splat_component.h) first in every frame:
// SplatComponent::update_lod() for each splat component of the scene, with the frame's camera and the
// engine's bus, and the work's status lines on the bus (plugin_msgs::BackgroundWork).
#include <string>
#include <utility>
#include <vector>

#include "engine/render/render_pass.h"
#include "splat_lod/splat_component.h"

namespace splat_lod {

class LodSwapPass : public engine::RenderPass {
public:
    // `source` names the plugin in the status messages.
    explicit LodSwapPass(std::string source = "splat_lod") : source_(std::move(source)) {}
    std::string name() const override { return "splat.lod_swap"; }
    int order() const override { return engine::pass_order::mesh - 50; }
    void execute(engine::FrameContext& frame) override;

private:
    std::string source_;
    std::vector<std::string> published_;  // the status lines last published
};

}  // namespace splat_lod
