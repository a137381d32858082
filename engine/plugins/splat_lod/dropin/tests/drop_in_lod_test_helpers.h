#pragma once
// The drop-in LOD's tests ("lod": "auto"): a small trained scene on disk, an engine whose splat
// component bakes in a couple of seconds, a small capture that imports as a world in a fraction of a
// second, and a cache folder of the test's own.
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "engine/scene/component_registry.h"
#include "splat_lod/core/cloud_transform.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/dropin/drop_in_lod.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_test_data.h"
#include "test_support.h"

namespace drop_in_lod_test {

namespace fs = std::filesystem;

// Sets an environment variable for one scope and restores it after.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const std::string& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        ::setenv(name, value.c_str(), 1);
    }
    ~ScopedEnv() {
        if (old_)
            ::setenv(name_, old_->c_str(), 1);
        else
            ::unsetenv(name_);
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    const char* name_;
    std::optional<std::string> old_;
};

// Sets `flag` when it goes out of scope: declared after the scene whose bake an observer holds until
// `flag`, it lets that bake go before a failed assertion closes the scene (which waits for the bake).
struct ReleaseOnExit {
    std::atomic<bool>& flag;
    ~ReleaseOnExit() { flag = true; }
};

// `folder`/scene.ply (lattice_cloud) and `folder`/scene.json with one splat component whose extra keys
// are `lod_keys` (e.g. R"(, "lod": "auto")"); returns the scene file.
inline fs::path write_scene(const fs::path& folder, const std::string& lod_keys) {
    fs::create_directories(folder);
    if (!fs::exists(folder / "scene.ply"))
        splat_lod::write_inria_ply(folder / "scene.ply", engine::test::lattice_cloud());
    const fs::path scene = folder / "scene.json";
    std::ofstream(scene) << R"({"nodes": [{"name": "cube", "components": [{"type": "splat", "asset": "scene.ply")"
                         << lod_keys << "}]}]}\n";
    return scene;
}

// A bake of about a second: few cameras, small images, few refinement iterations.
inline splat_lod::dropin::DropInLodSettings quick_settings() {
    splat_lod::dropin::DropInLodSettings settings;
    settings.setup.cameras = "rings:2x4";
    settings.setup.width = 128;
    settings.setup.height = 128;
    settings.setup.options.refine_iterations = 20;
    settings.setup.options.refine_cameras = 4;
    settings.setup.options.threads = 2;
    return settings;
}

// An engine with the splat_lod plugin whose "splat" type bakes with `settings`.
inline std::unique_ptr<engine::Engine> make_engine(splat_lod::dropin::DropInLodSettings settings = quick_settings()) {
    auto engine = std::make_unique<engine::Engine>();
    engine->plugins().add_static(splat_lod::make_plugin(splat_lod::dropin::make_drop_in(std::move(settings))));
    return engine;
}

// A 32 × 32 unit patch of flat ground (y up, 80 × 80 Gaussians) with three huge sky Gaussians above it,
// stored as a Y-down file would hold it (a half turn about x), so that the import has a frame to undo.
inline splat_lod::SplatCloud ground_capture() {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    splat_lod::SplatCloud cloud;
    cloud.resize(80 * 80 + 3);
    std::size_t k = 0;
    for (int i = 0; i < 80; ++i)
        for (int j = 0; j < 80; ++j, ++k) {
            cloud.positions[k] = {-16.0f + 0.4f * static_cast<float>(i), 0.05f * unit(rng),
                                  -16.0f + 0.4f * static_cast<float>(j)};
            cloud.log_scales[k] = {std::log(0.25f), std::log(0.01f), std::log(0.25f)};
            cloud.opacity_logits[k] = 3.0f;
            cloud.sh_dc[k] = {0.6f * unit(rng), 0.8f * unit(rng), 0.1f};
        }
    for (int sky = 0; sky < 3; ++sky, ++k) {
        cloud.positions[k] = {-8.0f + 8.0f * static_cast<float>(sky), 25.0f, 3.0f};
        cloud.log_scales[k] = glm::vec3(std::log(30.0f));
        cloud.opacity_logits[k] = -3.0f;
        cloud.sh_dc[k] = {0.2f, 0.4f, 1.0f};
    }
    splat_lod::transform_cloud(cloud, splat_lod::rotation_between({0, 1, 0}, {0, -1, 0}), glm::dvec3(0.0));
    return cloud;
}

// `folder`/capture.ply and `folder`/capture.json drawing it with "lod": "auto"; returns the scene file.
inline fs::path write_capture_scene(const fs::path& folder) {
    fs::create_directories(folder);
    splat_lod::write_inria_ply(folder / "capture.ply", ground_capture());
    const fs::path scene = folder / "capture.json";
    std::ofstream(scene) << R"({"nodes": [{"name": "cube", "components": [{"type": "splat", "asset": "capture.ply", )"
                         << R"("lod": "auto"}]}]})"
                         << "\n";
    return scene;
}

// Every capture is a world here; a quick import (small chunks and cameras, no refinement) and streaming
// in the calling thread.
inline splat_lod::dropin::DropInLodSettings world_settings(const fs::path& cache) {
    auto settings = quick_settings();
    settings.cache_folder = cache;
    settings.world_advice = [](const splat_lod::SplatCloud& cloud) {
        return "a capture of " + std::to_string(cloud.size());
    };
    settings.import.max_chunk_gaussians = 1024;
    settings.import.bake.refine_iterations = 0;
    settings.import.bake_width = 64;
    settings.import.bake_height = 64;
    settings.import.threads = 2;
    settings.streaming.background_thread = false;
    return settings;
}

inline splat_lod::SplatComponent& splat_of(engine::Scene& scene) {
    return *scene.find_node("cube")->find_component<splat_lod::SplatComponent>();
}

// Every name in `folder` (none when it does not exist).
inline std::vector<std::string> entries(const fs::path& folder) {
    std::vector<std::string> names;
    if (!fs::exists(folder)) return names;
    for (const auto& item : fs::directory_iterator(folder)) names.push_back(item.path().filename().string());
    return names;
}

}  // namespace drop_in_lod_test
