#pragma once
// Implemented in a file CMake generates for each tool (engine_link_static_plugins() in
// cmake/EnginePlugin.cmake): starts every plugin registered with engine_register_static_plugin().
namespace engine {
class PluginManager;
}

void engine_add_static_plugins(engine::PluginManager& plugins);
