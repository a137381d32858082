#pragma once
// The splat component beside a "mesh" component whose glTF file holds KHR_gaussian_splatting primitives
// (engine::ComponentRegistry::add_companion); the plugin registers it at startup.
#include <string>

namespace engine {
class ComponentRegistry;
}

namespace splat_lod {

void register_gltf_splat_companion(engine::ComponentRegistry& registry, const std::string& owner);

}  // namespace splat_lod
