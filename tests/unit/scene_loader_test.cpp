#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/assets/asset_cache.h"
#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/scene/builtin_components.h"
#include "engine/scene/component_registry.h"
#include "engine/scene/scene_loader.h"
#include "test_support.h"

namespace {

struct SceneLoaderTest : ::testing::Test {
    engine::ComponentRegistry registry;
    engine::AssetCache assets;
    SceneLoaderTest() { engine::register_builtin_components(registry); }

    std::unique_ptr<engine::Scene> load(const std::string& text) {
        return engine::load_scene_text(text, engine::test::source_dir() / "data/scenes/inline.json", registry, assets);
    }
    std::string error_of(const std::string& text) {
        try {
            load(text);
        } catch (const engine::Error& e) {
            return e.what();
        }
        return "(no error)";
    }
};

bool near(const glm::vec3& a, const glm::vec3& b) {
    return glm::length(a - b) < 1e-5f;
}

}  // namespace

TEST_F(SceneLoaderTest, BuildsHierarchyWithTransformsAndComponents) {
    const auto scene = load(R"({
        "background": [0.1, 0.2, 0.3],
        "nodes": [
          {"name": "parent", "translation": [1, 0, 0], "rotation_euler_deg": [0, 90, 0], "scale": 2,
           "children": [{"name": "child", "translation": [0, 0, -1],
                         "components": [{"type": "camera", "fov_y_deg": 60, "znear": 0.5, "zfar": 50}]}]},
          {"name": "sun", "rotation": [0, 0, 0, 1], "components": [{"type": "light", "kind": "ambient", "intensity": 0.5}]}
        ]})");
    EXPECT_TRUE(near(scene->background, {0.1f, 0.2f, 0.3f}));
    auto* child = scene->find_node("child");
    ASSERT_NE(child, nullptr);
    ASSERT_EQ(child->parent()->name(), "parent");
    // (0,0,-1) scaled by 2 and turned 90° about +Y becomes (−2,0,0); plus the parent's (1,0,0).
    const glm::vec3 world = glm::vec3(child->world_matrix() * glm::vec4(0, 0, 0, 1));
    EXPECT_TRUE(near(world, {-1.0f, 0.0f, 0.0f})) << world.x << "," << world.y << "," << world.z;
    const auto cameras = scene->components<engine::CameraComponent>();
    ASSERT_EQ(cameras.size(), 1u);
    EXPECT_FLOAT_EQ(cameras[0]->fov_y_deg, 60.0f);
    EXPECT_EQ(cameras[0]->node(), child);
    const auto lights = scene->components<engine::LightComponent>();
    ASSERT_EQ(lights.size(), 1u);
    EXPECT_EQ(lights[0]->kind, engine::LightComponent::Kind::ambient);
}

TEST_F(SceneLoaderTest, LookAtPointsMinusZAtTheTarget) {
    const auto scene = load(R"({"nodes": [{"name": "cam", "translation": [3, 4, 5], "look_at": [0, 1, 0]}]})");
    const glm::mat4 m = scene->find_node("cam")->world_matrix();
    const glm::vec3 forward = -glm::vec3(m[2]);
    EXPECT_TRUE(near(forward, glm::normalize(glm::vec3(-3, -3, -5))));
    EXPECT_GT(glm::vec3(m[1]).y, 0.0f);  // up stays up
}

TEST_F(SceneLoaderTest, CorruptJsonNamesTheFile) {
    const std::string e = error_of(R"({"nodes": [ {"name": "a", )");
    EXPECT_NE(e.find("inline.json"), std::string::npos) << e;
    EXPECT_NE(e.find("not valid JSON"), std::string::npos) << e;
}

TEST_F(SceneLoaderTest, UnknownComponentTypeNamesTheKeyAndTheKnownTypes) {
    const std::string e = error_of(R"({"nodes": [{"name": "a"}, {"components": [{"type": "meshh"}]}]})");
    EXPECT_NE(e.find("inline.json: nodes[1].components[0].type: unknown component type 'meshh'"), std::string::npos)
        << e;
    EXPECT_NE(e.find("camera, light, mesh"), std::string::npos) << e;
}

TEST_F(SceneLoaderTest, WrongValuesNameTheirKeys) {
    EXPECT_NE(error_of(R"({"nodes": [{"translation": [1, 2]}]})").find("nodes[0].translation: expected an array of 3"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"nodes": [{"components": [{"type": "camera", "fov_y_deg": "wide"}]}]})")
                  .find("nodes[0].components[0].fov_y_deg: expected a number"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"nodes": [{"components": [{"type": "camera", "fov_y_deg": 200}]}]})")
                  .find("fov_y_deg: must be in"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"nodes": [{"components": [{"type": "light", "kind": "spot"}]}]})")
                  .find("unknown light kind 'spot'"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"nodes": [{"components": [{"type": "mesh", "asset": "a.glb", "late": "yes"}]}]})")
                  .find("nodes[0].components[0].late: expected true or false"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"nodes": [{"rotation": [0, 0, 0, 0]}]})").find("nodes[0].rotation: zero quaternion"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"nodes": [{"transltion": [0, 0, 0]}]})").find("nodes[0].transltion: unknown key"),
              std::string::npos);
    EXPECT_NE(
        error_of(R"({"nodes": [{"components": [{"fov_y_deg": 3}]}]})").find("nodes[0].components[0].type: missing"),
        std::string::npos);
    EXPECT_NE(error_of(R"({"scene": []})").find("scene: unknown key"), std::string::npos);
    EXPECT_NE(error_of(R"([1, 2])").find("top level must be an object"), std::string::npos);
    EXPECT_NE(error_of(R"({"nodes": [{"translation": [1, 2, 1e999]}]})").find("inline.json"), std::string::npos);
}

TEST_F(SceneLoaderTest, MissingMeshAssetNamesSceneKeyAndAssetPath) {
    const std::string e = error_of(R"({"nodes": [{"components": [{"type": "mesh", "asset": "no/such/model.glb"}]}]})");
    EXPECT_NE(e.find("inline.json: nodes[0].components[0].asset"), std::string::npos) << e;
    EXPECT_NE(e.find("model.glb: file not found"), std::string::npos) << e;
}

TEST_F(SceneLoaderTest, MissingSceneFileIsAClearError) {
    try {
        engine::load_scene_file("/nonexistent/scene.json", registry, assets);
        FAIL();
    } catch (const engine::Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json: cannot open"), std::string::npos) << e.what();
    }
}

// A plugin's companions of a component type are attached beside it, from the same JSON, in owner
// order; removing an owner's companions leaves the others, and a second one from an owner is refused.
TEST_F(SceneLoaderTest, CompanionsAreAttachedBesideTheirComponent) {
    const auto light_beside = [](float intensity) {
        return [intensity](const nlohmann::json& spec, const engine::ComponentLoadContext&) {
            std::vector<std::unique_ptr<engine::Component>> out;
            if (spec.value("kind", "") != "ambient") return out;  // only beside ambient lights
            auto light = std::make_unique<engine::LightComponent>();
            light->intensity = intensity;
            out.push_back(std::move(light));
            return out;
        };
    };
    registry.add_companion("light", light_beside(2.0f), "plugin_b");
    registry.add_companion("light", light_beside(1.0f), "plugin_a");
    EXPECT_THROW(registry.add_companion("light", light_beside(3.0f), "plugin_a"), engine::Error);
    const std::string text = R"({"nodes": [
        {"name": "sun", "components": [{"type": "light", "kind": "ambient", "intensity": 0.5}]},
        {"name": "key", "components": [{"type": "light", "kind": "directional"}]}]})";
    auto scene = load(text);
    const auto& sun = scene->find_node("sun")->components();
    ASSERT_EQ(sun.size(), 3u);
    EXPECT_FLOAT_EQ(dynamic_cast<engine::LightComponent&>(*sun[0]).intensity, 0.5f);
    EXPECT_FLOAT_EQ(dynamic_cast<engine::LightComponent&>(*sun[1]).intensity, 1.0f) << "plugin_a before plugin_b";
    EXPECT_FLOAT_EQ(dynamic_cast<engine::LightComponent&>(*sun[2]).intensity, 2.0f);
    EXPECT_EQ(scene->find_node("key")->components().size(), 1u) << "nothing beside a directional light";
    registry.remove_companions("plugin_a");
    scene = load(text);
    EXPECT_EQ(scene->find_node("sun")->components().size(), 2u);
}
