// A plugin compiled with the old libstdc++ std::string ABI (_GLIBCXX_USE_CXX11_ABI=0). It uses
// no engine function, so dlopen() succeeds and only the build-info check can refuse it; a real
// plugin like this would hand the engine std::strings of the wrong layout.
#include "engine/plugin/plugin_abi.h"

namespace {

class OldStringAbiPlugin final : public engine::Plugin {
public:
    std::string name() const override { return "old_string_abi_plugin"; }
    std::string version() const override { return "1.0.0"; }
    void startup(engine::PluginContext&) override {}
    void shutdown(engine::PluginContext&) override {}
};

}  // namespace

ENGINE_EXPORT_PLUGIN(OldStringAbiPlugin)
