#pragma once
// The engine's services in one place: component registry (with the built-in mesh, camera and
// light types), asset cache, message bus, renderer (with the mesh pass) and plugins.
// Construction needs no GL context; rendering does.
#include <filesystem>
#include <memory>

#include "engine/assets/asset_cache.h"
#include "engine/core/message_bus.h"
#include "engine/plugin/plugin_manager.h"
#include "engine/render/renderer.h"
#include "engine/scene/component_registry.h"
#include "engine/scene/scene.h"

namespace engine {

class Engine {
public:
    Engine();
    ~Engine();  // shuts plugins down in reverse order of startup
    Engine(const Engine&) = delete;
    Engine& operator=(const Engine&) = delete;

    ComponentRegistry& components() { return components_; }
    AssetCache& assets() { return assets_; }
    MessageBus& bus() { return bus_; }
    Renderer& renderer() { return renderer_; }
    PluginManager& plugins() { return plugins_; }
    PluginContext plugin_context();

    // Loads a scene file; errors name the file and the key (see scene/scene_loader.h).
    std::unique_ptr<Scene> load_scene(const std::filesystem::path& path);

private:
    ComponentRegistry components_;
    AssetCache assets_;
    MessageBus bus_;
    Renderer renderer_;
    PluginManager plugins_;
};

}  // namespace engine
