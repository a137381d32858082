#include "splat_lod/splat_lod_plugin.h"

#include <cstdlib>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/message_bus.h"
#include "engine/engine.h"
#include "engine/render/renderer.h"
#include "engine/scene/component_registry.h"
#include "module/gltf_splat_companion.h"
#include "module/lod_update_pass.h"
#include "passes/splat_pass.h"
#include "splat_lod/lod_panel.h"
#include "splat_lod/splat_component.h"

namespace splat_lod {
namespace {

class SplatLodPlugin : public engine::Plugin {
public:
    explicit SplatLodPlugin(DropInLod drop_in) : drop_in_(std::move(drop_in)) {}

    // From the plugin's descriptor, engine/plugins/splat_lod/plugin.json.
    std::string name() const override { return SPLAT_LOD_PLUGIN_NAME; }
    std::string version() const override { return SPLAT_LOD_PLUGIN_VERSION; }

    void startup(engine::PluginContext& context) override {
        register_splat_component(context.components, name(), drop_in_);
        register_gltf_splat_companion(context.components, name());  // the splats of a glTF mesh asset
        context.renderer.add_shader_root(shader_dir());
        context.renderer.add_pass(std::make_shared<LodSwapPass>(name()));  // "lod": "auto" (lod_update_pass.h)
        auto pass = std::make_shared<SplatPass>();
        // Settings arrive as plugin_msgs::LodSettings from the UI, tools or the game.
        settings_ = context.bus.subscribe<plugin_msgs::LodSettings>(
            [pass = pass.get()](const plugin_msgs::LodSettings& lod) { pass->apply(lod); });
        context.renderer.add_pass(std::move(pass));
    }

    void add_ui_panels(engine::UiOverlay& overlay, engine::MessageBus& bus) override { add_lod_panel(overlay, bus); }

    void shutdown(engine::PluginContext& context) override {
        settings_.reset();
        context.renderer.remove_pass("splat");
        context.renderer.remove_pass(LodSwapPass().name());
        context.components.remove("splat");
        context.components.remove_companions(name());
    }

private:
    DropInLod drop_in_;
    engine::Subscription settings_;
};

}  // namespace

std::unique_ptr<engine::Plugin> make_plugin() {
    return make_plugin(DropInLod{});
}

std::unique_ptr<engine::Plugin> make_plugin(DropInLod drop_in) {
    return std::make_unique<SplatLodPlugin>(std::move(drop_in));
}

std::filesystem::path shader_dir() {
    if (const char* env = std::getenv("SPLAT_LOD_SHADER_DIR"); env != nullptr && env[0] != '\0') return env;
    return SPLAT_LOD_DEFAULT_SHADER_DIR;
}

SplatPass* find_splat_pass(engine::Renderer& renderer) {
    return dynamic_cast<SplatPass*>(renderer.find_pass("splat"));
}

plugin_msgs::SplatStatistics render_complete(engine::Engine& engine, const engine::Scene& scene,
                                             const engine::CameraView& camera, engine::RenderTarget& target,
                                             int max_attempts) {
    SplatPass* pass = find_splat_pass(engine.renderer());
    if (pass == nullptr) engine::fail("splat_lod::render_complete(): the splat_lod plugin is not started");
    for (int attempt = 0; attempt < max_attempts; ++attempt) {
        engine.renderer().render(scene, camera, target);
        pass->wait_for_statistics(engine.bus());
        const auto& stats = pass->latest_statistics();
        if (!stats) return {};  // no splat component drew anything
        if (!stats->overflowed) return *stats;
    }
    engine::fail("splat_lod::render_complete(): the key buffer still overflowed after " + std::to_string(max_attempts) +
                 " frames");
}

}  // namespace splat_lod
