#include "engine/scene/component_registry.h"

#include "engine/core/error.h"

namespace engine {

std::filesystem::path ComponentLoadContext::resolve(const std::string& asset) const {
    const std::filesystem::path p(asset);
    if (p.is_absolute()) return p;
    return (scene_file.parent_path() / p).lexically_normal();
}

void ComponentLoadContext::error(const std::string& field, const std::string& message) const {
    const std::string where = key.empty() ? field : (field.empty() ? key : key + "." + field);
    fail(scene_file.string() + ": " + where + ": " + message);
}

void ComponentRegistry::add(const std::string& type, ComponentFactory factory, const std::string& owner) {
    const auto it = factories_.find(type);
    if (it != factories_.end())
        fail("component type '" + type + "' is already registered by " + it->second.owner + " (registering " + owner +
             ")");
    factories_.emplace(type, Entry{std::move(factory), owner});
}

void ComponentRegistry::remove(const std::string& type) {
    factories_.erase(type);
}

std::vector<std::string> ComponentRegistry::types() const {
    std::vector<std::string> out;
    for (const auto& [name, entry] : factories_) out.push_back(name);
    return out;
}

std::unique_ptr<Component> ComponentRegistry::create(const std::string& type, const nlohmann::json& spec,
                                                     const ComponentLoadContext& context) const {
    const auto it = factories_.find(type);
    if (it == factories_.end()) {
        std::string known;
        for (const auto& t : types()) known += (known.empty() ? "" : ", ") + t;
        context.error("type", "unknown component type '" + type + "' (known: " + known + ")");
    }
    return it->second.factory(spec, context);
}

}  // namespace engine
