#include "splat_lod/splat_lod_plugin.h"

#include "engine/render/renderer.h"
#include "engine/scene/component_registry.h"
#include "passes/splat_pass.h"
#include "splat_lod/splat_component.h"

namespace splat_lod {
namespace {

class SplatLodPlugin : public engine::Plugin {
public:
    std::string name() const override { return "splat_lod"; }
    std::string version() const override { return "0.1.0"; }

    void startup(engine::PluginContext& context) override {
        register_splat_component(context.components, name());
        context.renderer.add_pass(std::make_shared<SplatPass>());
    }

    void shutdown(engine::PluginContext& context) override {
        context.renderer.remove_pass("splat");
        context.components.remove("splat");
    }
};

}  // namespace

std::unique_ptr<engine::Plugin> make_plugin() { return std::make_unique<SplatLodPlugin>(); }

SplatPass* find_splat_pass(engine::Renderer& renderer) { return dynamic_cast<SplatPass*>(renderer.find_pass("splat")); }

}  // namespace splat_lod
