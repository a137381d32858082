#pragma once
// The splat_lod plugin: registers the "splat" component type and the splat render pass (its public
// handle: splat_lod/splat_renderer.h).
//   engine.plugins().add_static(splat_lod::make_plugin());
// With the optional drop-in LOD ("lod": "auto"), splat_lod::dropin::make_plugin() makes the same
// plugin with it (splat_lod/dropin/drop_in_lod.h); programs that start the engine's static plugins get
// that one when the build has it (SPLAT_LOD_DROP_IN, on by default).
#include <filesystem>
#include <memory>

#include "splat_lod/msgs/splat_statistics.h"

#include "engine/plugin/plugin.h"
#include "splat_lod/splat_component.h"

namespace engine {
class Engine;
class Scene;
class RenderTarget;
struct CameraView;
}  // namespace engine

namespace splat_lod {

// Without a drop-in LOD: "lod": "auto" draws the file as it is. (No default argument: the engine's
// generated list of static plugins declares the factory without parameters.)
std::unique_ptr<engine::Plugin> make_plugin();
// `drop_in`: what "lod": "auto" does (splat_component.h).
std::unique_ptr<engine::Plugin> make_plugin(DropInLod drop_in);

// The folder of the plugin's shaders (the shader library's root for "splat_lod/..." files): the
// environment's SPLAT_LOD_SHADER_DIR, else runtime/shaders in the source tree. The plugin adds it to the
// renderer's shader roots at startup.
std::filesystem::path shader_dir();

// For tools and tests (it waits for the GPU): renders the frame again while it needed more
// tile-splat pairs than the key buffer held (the buffer grows after each such frame), and
// returns the complete frame's statistics. Throws after `max_attempts` frames.
plugin_msgs::SplatStatistics render_complete(engine::Engine& engine, const engine::Scene& scene,
                                             const engine::CameraView& camera, engine::RenderTarget& target,
                                             int max_attempts = 8);

}  // namespace splat_lod
