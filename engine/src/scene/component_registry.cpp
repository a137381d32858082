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

void ComponentRegistry::add_companion(const std::string& type, CompanionFactory factory, const std::string& owner) {
    if (!companions_[type].emplace(owner, std::move(factory)).second)
        fail("a companion of component type '" + type + "' is already registered by " + owner);
}

void ComponentRegistry::remove_companions(const std::string& owner) {
    for (auto& [type, owners] : companions_) owners.erase(owner);
}

std::vector<std::unique_ptr<Component>> ComponentRegistry::create_companions(
    const std::string& type, const nlohmann::json& spec, const ComponentLoadContext& context) const {
    std::vector<std::unique_ptr<Component>> out;
    const auto it = companions_.find(type);
    if (it == companions_.end()) return out;
    for (const auto& [owner, factory] : it->second)
        for (auto& c : factory(spec, context))
            if (c) out.push_back(std::move(c));
    return out;
}

}  // namespace engine
