#include "engine/engine.h"

#include "engine/render/mesh_pass.h"
#include "engine/scene/builtin_components.h"
#include "engine/scene/scene_loader.h"

namespace engine {

Engine::Engine() : renderer_(bus_, assets_), plugins_(plugin_context()) {
    register_builtin_components(components_);
    renderer_.add_pass(std::make_shared<MeshPass>(MeshStage::early));
    renderer_.add_pass(std::make_shared<MeshPass>(MeshStage::late));
}

Engine::~Engine() {
    plugins_.shutdown_all();
}

PluginContext Engine::plugin_context() {
    return PluginContext{components_, renderer_, bus_, assets_};
}

std::unique_ptr<Scene> Engine::load_scene(const std::filesystem::path& path) {
    return load_scene_file(path, components_, assets_);
}

}  // namespace engine
