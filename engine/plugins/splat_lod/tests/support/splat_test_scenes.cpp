#include "splat_test_scenes.h"

#include "engine/render/render_target.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "test_support.h"

namespace engine::test {

SplatRenderHarness::SplatRenderHarness() : engine_(std::make_unique<Engine>()) {
    engine_->plugins().add_static(splat_lod::make_plugin());
}
SplatRenderHarness::~SplatRenderHarness() = default;

Image SplatRenderHarness::render(const std::vector<std::shared_ptr<const splat_lod::SplatCloud>>& clouds,
                                 const CameraView& camera, const glm::vec3& background,
                                 const std::vector<glm::mat4>& models) {
    Scene scene;
    scene.background = background;
    for (std::size_t i = 0; i < clouds.size(); ++i) {
        auto component = std::make_unique<splat_lod::SplatComponent>();
        component->cloud = clouds[i];
        Node& node = scene.root().add_child("splats " + std::to_string(i));
        if (i < models.size()) {
            // Decompose only what the tests use: translation, rotation, uniform scale.
            const glm::mat4& m = models[i];
            const float scale = glm::length(glm::vec3(m[0]));
            node.transform().scale = glm::vec3(scale);
            node.transform().rotation = glm::quat_cast(glm::mat3(m) / scale);
            node.transform().translation = glm::vec3(m[3]);
        }
        node.attach(std::move(component));
    }
    RenderTarget target(camera.width, camera.height);
    splat_lod::render_complete(*engine_, scene, camera, target);
    return target.read_color();
}

splat_lod::reference::MeshLayer mesh_layer(const RenderTarget& target) {
    const Image colour = target.read_color();
    const std::vector<float> depth = target.read_view_depth();
    splat_lod::reference::MeshLayer layer{colour.width, colour.height, {}, {}};
    for (std::size_t i = 0; i < depth.size(); ++i) {
        layer.depth.push_back(depth[i]);
        const auto* p = &colour.rgba[i * 4];
        layer.colour.push_back(glm::dvec3(p[0], p[1], p[2]) / 255.0);
    }
    return layer;
}

void SplatRenderHarness::edit_lod(const std::function<void(plugin_msgs::LodSettings&)>& edit) {
    plugin_msgs::LodSettings lod = splat_lod::SplatRenderer(engine_->renderer()).lod();
    edit(lod);
    engine_->bus().publish(lod);
}

}  // namespace engine::test
