#pragma once
// The drop-in LOD's tests ("lod": "auto"): a small trained scene on disk, an engine whose splat
// component bakes in a couple of seconds, and a cache folder of the test's own.
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "engine/scene/component_registry.h"
#include "splat_lod/core/splat_io.h"
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
inline splat_lod::DropInLodSettings quick_settings() {
    splat_lod::DropInLodSettings settings;
    settings.setup.cameras = "rings:2x4";
    settings.setup.width = 128;
    settings.setup.height = 128;
    settings.setup.options.refine_iterations = 20;
    settings.setup.options.refine_cameras = 4;
    settings.setup.options.threads = 2;
    return settings;
}

// An engine with the splat_lod plugin whose "splat" type bakes with `settings`.
inline std::unique_ptr<engine::Engine> make_engine(splat_lod::DropInLodSettings settings = quick_settings()) {
    auto engine = std::make_unique<engine::Engine>();
    engine->plugins().add_static(splat_lod::make_plugin());
    engine->components().remove("splat");
    splat_lod::register_splat_component(engine->components(), "test", std::move(settings));
    return engine;
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
