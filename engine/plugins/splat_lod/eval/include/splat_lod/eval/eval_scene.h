#pragma once
// The scene an evaluation renders: a splat file on its own (black background, stored axes) or a
// scene JSON (its splat components, meshes and lights), and where its Gaussians are.
#include <filesystem>
#include <memory>

#include "engine/engine.h"
#include "splat_lod/core/camera_set.h"
#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::eval {

struct EvalScene {
    std::unique_ptr<engine::Scene> scene;
    SceneExtent extent;
};

EvalScene make_splat_scene(std::shared_ptr<const SplatCloud> cloud, const std::filesystem::path& asset = {});
EvalScene load_splat_file_scene(const std::filesystem::path& path);
// Throws engine::Error when the scene has no splat component.
EvalScene load_json_scene(engine::Engine& engine, const std::filesystem::path& path);

// The robust extent of every splat component's Gaussian centres in world space.
SceneExtent splat_extent(const engine::Scene& scene);

}  // namespace splat_lod::eval
