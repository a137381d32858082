// The showcase scenes in content/scenes/ (meshes with this plugin's splats) load from a fresh clone.
#include <filesystem>

#include <gtest/gtest.h>

#include "engine/assets/asset_cache.h"
#include "engine/core/file_io.h"
#include "engine/scene/builtin_components.h"
#include "engine/scene/component_registry.h"
#include "engine/scene/scene_loader.h"
#include "splat_lod/splat_component.h"
#include "test_support.h"

namespace {

// Every showcase scene loads from the repository alone: none names a file of the shared data folder, so
// a fresh clone renders them all.
TEST(ShowcaseScenes, EveryOneLoadsFromTheRepositoryAlone) {
    engine::ComponentRegistry registry;
    engine::AssetCache assets;
    engine::register_builtin_components(registry);
    splat_lod::register_splat_component(registry, "splat_lod");  // the scenes use the plugin's type
    int loaded = 0;
    for (const auto& entry : std::filesystem::directory_iterator(engine::test::repo_dir() / "content/scenes")) {
        if (entry.path().extension() != ".json") continue;
        SCOPED_TRACE(entry.path().string());
        EXPECT_EQ(engine::read_text_file(entry.path()).find("shared/data/"), std::string::npos);
        const auto scene = engine::load_scene_file(entry.path(), registry, assets);
        EXPECT_FALSE(scene->components<engine::MeshComponent>().empty());
        EXPECT_TRUE(scene->world_bounds().has_value());
        ++loaded;
    }
    EXPECT_GE(loaded, 4) << "biker_with_boxes, box_textured, flight_helmet and fox_and_boxes";
}

}  // namespace
