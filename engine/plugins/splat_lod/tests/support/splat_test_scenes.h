#pragma once
// Splat scenes for the gpu tier: the test data of splat_test_data.h, and one-call GPU renders through
// the engine and the plugin.
#include <functional>
#include <memory>
#include <vector>

#include "engine/engine.h"
#include "engine/render/image.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/msgs/lod_settings.h"
#include "splat_test_data.h"

namespace engine::test {

// Renders splat clouds (each under its own node with `models[i]`) through Engine + splat_lod,
// re-rendering while the key buffer had to grow, and returns the colour.
// The mesh pass's result in `target` (colour and view depth, read back) as the CPU reference's mesh layer.
splat_lod::reference::MeshLayer mesh_layer(const RenderTarget& target);

class SplatRenderHarness {
public:
    SplatRenderHarness();
    ~SplatRenderHarness();
    Image render(const std::vector<std::shared_ptr<const splat_lod::SplatCloud>>& clouds, const CameraView& camera,
                 const glm::vec3& background = glm::vec3(0.0f), const std::vector<glm::mat4>& models = {});
    Engine& engine() { return *engine_; }
    // Publishes the splat pass's LOD settings as they are now with `edit` applied, on the engine's bus:
    // the one way they reach the pass.
    void edit_lod(const std::function<void(plugin_msgs::LodSettings&)>& edit);

private:
    std::unique_ptr<Engine> engine_;
};

}  // namespace engine::test
