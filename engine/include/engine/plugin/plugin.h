#pragma once
// A plugin adds component types and render passes at startup and removes exactly those at
// shutdown. Plugins link statically by default (PluginManager::add_static) and may also be
// loaded from a shared library at run time (PluginManager::load_shared, see plugin_abi.h).
//
// The manager removes any component type or render pass a plugin left registered, but a shared
// plugin's library is closed right after its shutdown, so nothing else whose code lives in it
// may outlive shutdown either: components it created (destroy those scenes first), asset-cache
// entries of its own types, and bus subscriptions (keep them as members of the plugin object).
#include <string>

namespace engine {

class ComponentRegistry;
class Renderer;
class MessageBus;
class AssetCache;
class UiOverlay;

// The engine services a plugin may extend or use.
struct PluginContext {
    ComponentRegistry& components;
    Renderer& renderer;
    MessageBus& bus;
    AssetCache& assets;
};

class Plugin {
public:
    virtual ~Plugin() = default;
    virtual std::string name() const = 0;
    virtual std::string version() const = 0;
    virtual void startup(PluginContext& context) = 0;
    virtual void shutdown(PluginContext& context) = 0;
    // Windowed applications call this once their overlay exists, for the plugin to add its panels.
    // The panels' code must outlive the overlay: a plugin loaded from a shared library (unloaded
    // at shutdown) should add none.
    virtual void add_ui_panels(UiOverlay& overlay, MessageBus& bus) {
        (void)overlay;
        (void)bus;
    }
};

}  // namespace engine
