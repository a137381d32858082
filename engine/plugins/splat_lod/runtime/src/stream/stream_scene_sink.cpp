#include "splat_lod/stream/stream_scene_sink.h"

#include <memory>

#include "engine/core/error.h"
#include "splat_lod/splat_component.h"

namespace splat_lod::world {

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
