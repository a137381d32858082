#pragma once
// The splat_lod plugin: registers the "splat" component type and the splat render pass.
//   engine.plugins().add_static(splat_lod::make_plugin());
#include <memory>

#include "engine/plugin/plugin.h"

namespace splat_lod {

class SplatPass;

std::unique_ptr<engine::Plugin> make_plugin();

// The plugin's pass in a running engine (nullptr when the plugin is not started), for tools and
// tests that change its settings or read its statistics.
SplatPass* find_splat_pass(engine::Renderer& renderer);

}  // namespace splat_lod
