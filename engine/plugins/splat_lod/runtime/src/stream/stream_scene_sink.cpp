#include "splat_lod/stream/stream_scene_sink.h"

#include <memory>

#include <glm/gtc/quaternion.hpp>

#include "engine/assets/asset_cache.h"
#include "engine/assets/mesh_asset.h"
#include "engine/core/error.h"
#include "engine/scene/builtin_components.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/splat_component.h"

namespace splat_lod::world {

namespace {

void attach_gltf(engine::Node& node, const std::filesystem::path& file, engine::AssetCache& assets, int sh_degree_cap) {
    const auto mesh = assets.mesh(file);  // each file loads once
    if (!mesh->primitives.empty()) {
        auto component = std::make_unique<engine::MeshComponent>();
        component->asset = file;
        component->mesh = mesh;
        node.attach(std::move(component));
    }
    if (mesh->splat_primitives == 0) return;
    auto splats = std::make_unique<SplatComponent>();
    splats->asset = file;
    splats->sh_degree_cap = sh_degree_cap;
    splats->cloud = std::make_shared<const SplatCloud>(read_gltf_splats(file));
    node.attach(std::move(splats));
}

}  // namespace

void add_world_props(engine::Node& parent, const WorldManifest& manifest, const std::filesystem::path& folder,
                     engine::AssetCache& assets, int sh_degree_cap) {
    for (std::size_t i = 0; i < manifest.props.size(); ++i) {
        const Prop& prop = manifest.props[i];
        engine::Node& node = parent.add_child(prop.mesh.stem().string() + " " + std::to_string(i));
        node.transform().translation = prop.translation;
        node.transform().rotation = glm::quat(glm::radians(prop.rotation_euler_deg));
        node.transform().scale = prop.scale;
        attach_gltf(node, folder / prop.mesh, assets, sh_degree_cap);
    }
    if (!manifest.terrain_mesh.empty())
        attach_gltf(parent.add_child("terrain"), folder / manifest.terrain_mesh, assets, sh_degree_cap);
}

SceneResidencySink::SceneResidencySink(engine::Node& root, int sh_degree_cap)
    : root_(root), sh_degree_cap_(sh_degree_cap) {}

void SceneResidencySink::upload(const LevelPart& part) {
    if (!part.gaussians)
        engine::fail("SceneResidencySink: " + part.chunk_id + " level " + std::to_string(part.level) +
                     " has no Gaussians");
    engine::Node& node =
        root_.add_child(part.chunk_id + " L" + std::to_string(part.level) + " part " + std::to_string(part.part));
    auto component = std::make_unique<SplatComponent>();
    component->cloud = part.gaussians;
    component->sh_degree_cap = sh_degree_cap_;
    component->visible = part.visible;
    component->opacity = part.opacity;
    component->dissolve = true;  // fades draw a growing share of the Gaussians, not all of them fainter
    node.attach(std::move(component));
    nodes_[{part.chunk_id, part.level}].push_back(&node);
}

void SceneResidencySink::release(const std::string& chunk_id, int level) {
    const auto it = nodes_.find({chunk_id, level});
    if (it == nodes_.end()) return;
    for (engine::Node* node : it->second) root_.remove_child(*node);
    nodes_.erase(it);
}

void SceneResidencySink::show(const std::string& chunk_id, bool visible) {
    for (auto it = nodes_.lower_bound({chunk_id, 0}); it != nodes_.end() && it->first.first == chunk_id; ++it)
        for (engine::Node* node : it->second)
            if (auto* component = node->find_component<SplatComponent>()) component->visible = visible;
}

void SceneResidencySink::fade(const std::string& chunk_id, int level, float opacity) {
    const auto it = nodes_.find({chunk_id, level});
    if (it == nodes_.end()) return;
    for (engine::Node* node : it->second)
        if (auto* component = node->find_component<SplatComponent>()) component->opacity = opacity;
}

std::size_t SceneResidencySink::resident_parts() const {
    std::size_t n = 0;
    for (const auto& [key, nodes] : nodes_) n += nodes.size();
    return n;
}

}  // namespace splat_lod::world
