#pragma once
// The splat_lod plugin: registers the "splat" component type and the splat render pass (its public
// handle: splat_lod/splat_renderer.h).
//   engine.plugins().add_static(splat_lod::make_plugin());
#include <memory>

#include <plugin_msgs/splat_statistics.h>

#include "engine/plugin/plugin.h"

namespace engine {
class Engine;
class Scene;
class RenderTarget;
struct CameraView;
}  // namespace engine

namespace splat_lod {

std::unique_ptr<engine::Plugin> make_plugin();

// For tools and tests (it waits for the GPU): renders the frame again while it needed more
// tile-splat pairs than the key buffer held (the buffer grows after each such frame), and
// returns the complete frame's statistics. Throws after `max_attempts` frames.
plugin_msgs::SplatStatistics render_complete(engine::Engine& engine, const engine::Scene& scene,
                                             const engine::CameraView& camera, engine::RenderTarget& target,
                                             int max_attempts = 8);

}  // namespace splat_lod
