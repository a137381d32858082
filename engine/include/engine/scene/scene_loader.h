#pragma once
// Scene files (content/scenes/*.json):
//   { "background": [r, g, b],                       display-space colour, optional
//     "nodes": [ { "name": "...",
//                  "translation": [x, y, z], "rotation": [x, y, z, w] | "rotation_euler_deg": [x, y, z],
//                  "scale": [x, y, z] | s, "look_at": [x, y, z] (points −Z at a world point),
//                  "components": [ { "type": "mesh" | "camera" | "light" | <plugin type>, ... } ],
//                  "children": [ ...nodes ] } ] }
// Errors throw engine::Error as "<file>: <key path>: <problem>", e.g.
// "scene.json: nodes[1].components[0].type: unknown component type 'meshh' (known: camera, light, mesh)".
#include <filesystem>
#include <memory>

#include "engine/scene/scene.h"

namespace engine {

class ComponentRegistry;
class AssetCache;

std::unique_ptr<Scene> load_scene_file(const std::filesystem::path& path, const ComponentRegistry& registry,
                                       AssetCache& assets);
// The same from text already in memory; `path` is used for messages and relative assets.
std::unique_ptr<Scene> load_scene_text(const std::string& text, const std::filesystem::path& path,
                                       const ComponentRegistry& registry, AssetCache& assets);

}  // namespace engine
