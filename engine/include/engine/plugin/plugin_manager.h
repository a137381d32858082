#pragma once
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/plugin/plugin.h"

namespace engine {

// Starts plugins and shuts them down in reverse order.
class PluginManager {
public:
    explicit PluginManager(PluginContext context);
    ~PluginManager();  // shutdown_all()

    // A plugin linked into the executable.
    Plugin& add_static(std::unique_ptr<Plugin> plugin);
    // dlopen()s a plugin library, checks its ABI version against ENGINE_PLUGIN_ABI_VERSION and
    // starts it. Errors name the library and say what mismatched.
    Plugin& load_shared(const std::filesystem::path& library);
    // Shuts one plugin down (and unloads its library, if any).
    void unload(const std::string& name);
    void shutdown_all();

    std::vector<std::string> names() const;
    Plugin* find(const std::string& name) const;

private:
    struct Loaded;
    Plugin& start(std::unique_ptr<Loaded> loaded);
    PluginContext context_;
    std::vector<std::unique_ptr<Loaded>> loaded_;
};

}  // namespace engine
