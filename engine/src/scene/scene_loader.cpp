#include "engine/scene/scene_loader.h"

#include <cmath>

#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/scene/component_registry.h"
#include "engine/scene/json_fields.h"

namespace engine {
namespace {

namespace jf = json_fields;

struct LoadState {
    std::filesystem::path file;
    const ComponentRegistry& registry;
    AssetCache& assets;
};

ComponentLoadContext context_for(const LoadState& state, const std::string& key) {
    return ComponentLoadContext{state.file, key, &state.assets};
}

void read_transform(const nlohmann::json& spec, Node& node, const ComponentLoadContext& ctx) {
    Transform& t = node.transform();
    t.translation = jf::vec3(spec, "translation", t.translation, ctx);
    if (spec.contains("rotation") && spec.contains("rotation_euler_deg"))
        ctx.error("rotation", "give either rotation or rotation_euler_deg, not both");
    if (spec.contains("rotation")) {
        // glTF order x, y, z, w; normalised in double, where the length of large values cannot overflow.
        const glm::dvec4 q(jf::vec4(spec, "rotation", glm::vec4(0, 0, 0, 1), ctx));
        const double length = glm::length(q);
        if (length < 1e-8) ctx.error("rotation", "zero quaternion");
        t.rotation = glm::quat(static_cast<float>(q.w / length), static_cast<float>(q.x / length),
                               static_cast<float>(q.y / length), static_cast<float>(q.z / length));
    }
    if (spec.contains("rotation_euler_deg"))
        t.rotation = glm::quat(glm::radians(jf::vec3(spec, "rotation_euler_deg", glm::vec3(0), ctx)));
    if (spec.contains("scale")) {
        if (spec["scale"].is_number())
            t.scale = glm::vec3(jf::number(spec, "scale", 1.0f, ctx));
        else
            t.scale = jf::vec3(spec, "scale", t.scale, ctx);
    }
    if (spec.contains("look_at")) {
        if (spec.contains("rotation") || spec.contains("rotation_euler_deg"))
            ctx.error("look_at", "give either a rotation or look_at, not both");
        const glm::vec3 target = jf::vec3(spec, "look_at", glm::vec3(0), ctx);
        const float distance = glm::length(target - t.translation);
        if (distance < 1e-8f) ctx.error("look_at", "target equals the node's translation");
        if (!std::isfinite(distance)) ctx.error("look_at", "target too far from the node's translation");
        t.rotation = Transform::look_rotation(t.translation, target, glm::vec3(0, 1, 0));
    }
}

void read_node(const nlohmann::json& spec, Node& parent, const std::string& key, const LoadState& state) {
    const ComponentLoadContext ctx = context_for(state, key);
    if (!spec.is_object()) ctx.error("", "expected an object, got " + spec.dump());
    jf::only_keys(
        spec, {"name", "translation", "rotation", "rotation_euler_deg", "scale", "look_at", "components", "children"},
        ctx);
    Node& node = parent.add_child(jf::string(spec, "name", key, ctx));
    read_transform(spec, node, ctx);

    if (const auto it = spec.find("components"); it != spec.end()) {
        if (!it->is_array()) ctx.error("components", "expected an array");
        for (std::size_t i = 0; i < it->size(); ++i) {
            const auto& component = (*it)[i];
            const auto cctx = context_for(state, key + ".components[" + std::to_string(i) + "]");
            if (!component.is_object()) cctx.error("", "expected an object");
            const std::string type = jf::required_string(component, "type", cctx);
            node.attach(state.registry.create(type, component, cctx));
            for (auto& companion : state.registry.create_companions(type, component, cctx))
                node.attach(std::move(companion));
        }
    }
    if (const auto it = spec.find("children"); it != spec.end()) {
        if (!it->is_array()) ctx.error("children", "expected an array");
        for (std::size_t i = 0; i < it->size(); ++i)
            read_node((*it)[i], node, key + ".children[" + std::to_string(i) + "]", state);
    }
}

}  // namespace

std::unique_ptr<Scene> load_scene_text(const std::string& text, const std::filesystem::path& path,
                                       const ComponentRegistry& registry, AssetCache& assets) {
    nlohmann::json document;
    try {
        document = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        fail(path.string() + ": not valid JSON: " + e.what());
    }
    const LoadState state{path, registry, assets};
    const ComponentLoadContext ctx = context_for(state, "");
    if (!document.is_object()) ctx.error("", "the top level must be an object");
    jf::only_keys(document, {"background", "nodes", "description"}, ctx);

    auto scene = std::make_unique<Scene>();
    scene->source_file = path;
    scene->background = jf::vec3(document, "background", scene->background, ctx);
    const auto nodes = document.find("nodes");
    if (nodes == document.end()) ctx.error("nodes", "missing (required)");
    if (!nodes->is_array()) ctx.error("nodes", "expected an array");
    for (std::size_t i = 0; i < nodes->size(); ++i)
        read_node((*nodes)[i], scene->root(), "nodes[" + std::to_string(i) + "]", state);
    return scene;
}

std::unique_ptr<Scene> load_scene_file(const std::filesystem::path& path, const ComponentRegistry& registry,
                                       AssetCache& assets) {
    return load_scene_text(read_text_file(path), path, registry, assets);
}

}  // namespace engine
