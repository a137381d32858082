#include "splat_lod/eval/eval_scene.h"

#include "engine/core/error.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/splat_component.h"

namespace splat_lod::eval {

SceneExtent splat_extent(const engine::Scene& scene) {
    std::vector<glm::vec3> points;
    for (const SplatComponent* splat : scene.components<SplatComponent>()) {
        if (!splat->cloud) continue;
        const glm::mat4 model = splat->node() ? splat->node()->world_matrix() : glm::mat4(1.0f);
        for (const auto& p : splat->cloud->positions) points.push_back(glm::vec3(model * glm::vec4(p, 1.0f)));
    }
    if (points.empty()) engine::fail("splat_lod::eval: the scene has no Gaussians to evaluate");
    return robust_extent(points);
}

EvalScene make_splat_scene(std::shared_ptr<const SplatCloud> cloud, const std::filesystem::path& asset) {
    EvalScene out;
    out.scene = std::make_unique<engine::Scene>();
    out.scene->background = glm::vec3(0.0f);
    auto splat = std::make_unique<SplatComponent>();
    splat->asset = asset;
    splat->cloud = std::move(cloud);
    out.scene->root().add_child("splats").attach(std::move(splat));
    out.extent = splat_extent(*out.scene);
    return out;
}

EvalScene load_splat_file_scene(const std::filesystem::path& path) {
    return make_splat_scene(std::make_shared<const SplatCloud>(load_splat_file(path, nullptr)), path);
}

EvalScene load_json_scene(engine::Engine& engine, const std::filesystem::path& path) {
    EvalScene out;
    out.scene = engine.load_scene(path);
    if (out.scene->components<SplatComponent>().empty())
        engine::fail(path.string() + ": the scene has no splat component");
    out.extent = splat_extent(*out.scene);
    return out;
}

}  // namespace splat_lod::eval
