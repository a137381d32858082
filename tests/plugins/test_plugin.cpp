#include "test_plugin.h"

#include <string>
#include <utility>

#include "engine/plugin/plugin_abi.h"
#include "engine/render/render_pass.h"
#include "engine/render/renderer.h"
#include "engine/scene/component_registry.h"
#include "engine/scene/json_fields.h"

namespace test_plugin {

// A component that only remembers the label of its scene entry.
class MarkerComponent final : public engine::Component {
public:
    explicit MarkerComponent(std::string label) : label_(std::move(label)) {}
    std::string_view type_name() const override { return "test_marker"; }
    const std::string& label() const { return label_; }

private:
    std::string label_;
};

std::unique_ptr<engine::Component> make_marker(const nlohmann::json& spec, const engine::ComponentLoadContext& ctx) {
    engine::json_fields::only_keys(spec, {"type", "label"}, ctx);
    return std::make_unique<MarkerComponent>(engine::json_fields::string(spec, "label", "", ctx));
}

// GL-free so that the unit tier can run it; it only counts the frames it took part in.
class CountingPass final : public engine::RenderPass {
public:
    std::string name() const override { return "test_plugin.pass"; }
    int order() const override { return engine::pass_order::plugin; }
    void execute(engine::FrameContext&) override { ++executions_; }
    int executions() const { return executions_; }

private:
    int executions_ = 0;
};

class TestPlugin final : public engine::Plugin {
public:
    std::string name() const override { return "test_plugin"; }
    std::string version() const override { return "1.0.0"; }

    void startup(engine::PluginContext& context) override {
        context.components.add("test_marker", make_marker, name());
        context.renderer.add_pass(std::make_shared<CountingPass>());
    }

    void shutdown(engine::PluginContext& context) override {
        context.renderer.remove_pass("test_plugin.pass");
        context.components.remove("test_marker");
    }
};

}  // namespace test_plugin

std::unique_ptr<engine::Plugin> make_test_plugin() {
    return std::make_unique<test_plugin::TestPlugin>();
}

#if defined(TEST_PLUGIN_SHARED)
ENGINE_EXPORT_PLUGIN(test_plugin::TestPlugin)
#endif
