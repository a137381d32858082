#pragma once
// Maps a component type name in scene files to a factory. The engine registers its built-in
// types; plugins add theirs at startup and remove them at shutdown.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene/component.h"

namespace engine {

class AssetCache;

// What a factory knows about where its JSON came from, for paths and error messages.
struct ComponentLoadContext {
    std::filesystem::path scene_file;
    std::string key;  // e.g. "nodes[2].components[0]"
    AssetCache* assets = nullptr;

    // An asset path from the scene file, relative to the scene file's folder.
    std::filesystem::path resolve(const std::string& asset) const;
    // Throws engine::Error as "<scene_file>: <key>.<field>: <message>".
    [[noreturn]] void error(const std::string& field, const std::string& message) const;
};

using ComponentFactory =
    std::function<std::unique_ptr<Component>(const nlohmann::json& spec, const ComponentLoadContext& context)>;
// Components a plugin attaches beside one of another type, made from the same JSON: for instance the
// splats of a glTF file that a "mesh" component names. Returns none when it has nothing to add.
using CompanionFactory = std::function<std::vector<std::unique_ptr<Component>>(const nlohmann::json& spec,
                                                                               const ComponentLoadContext& context)>;

class ComponentRegistry {
public:
    // Throws when the type is already registered (by `owner`, e.g. "engine" or a plugin name).
    void add(const std::string& type, ComponentFactory factory, const std::string& owner = "engine");
    void remove(const std::string& type);
    bool contains(const std::string& type) const { return factories_.count(type) != 0; }
    std::vector<std::string> types() const;

    std::unique_ptr<Component> create(const std::string& type, const nlohmann::json& spec,
                                      const ComponentLoadContext& context) const;

    // Companions of `type`, one factory per owner (a second from the same owner throws); the scene
    // loader attaches what they return after the component itself, in the owners' order.
    void add_companion(const std::string& type, CompanionFactory factory, const std::string& owner);
    void remove_companions(const std::string& owner);
    std::vector<std::unique_ptr<Component>> create_companions(const std::string& type, const nlohmann::json& spec,
                                                              const ComponentLoadContext& context) const;

private:
    struct Entry {
        ComponentFactory factory;
        std::string owner;
    };
    std::map<std::string, Entry> factories_;
    std::map<std::string, std::map<std::string, CompanionFactory>> companions_;  // type → owner → factory
};

}  // namespace engine
