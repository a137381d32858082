#include <cmath>

#include <plugin_msgs/frame_statistics.h>

#include "engine/core/error.h"
#include "engine/engine.h"
#include "engine/render/fog_pass.h"
#include "engine/render/picking.h"
#include "engine/render/render_target.h"
#include "engine/render/scene_camera.h"
#include "engine/scene/builtin_components.h"
#include "engine/scene/scene_loader.h"
#include "gpu_fixture.h"
#include "test_support.h"

namespace {

class MeshPassTest : public engine::test::GpuTest {
protected:
    engine::Engine engine;

    std::unique_ptr<engine::Scene> scene_with(const std::string& asset, const std::string& extra_nodes = "") {
        const std::string text = R"({"background": [0.2, 0.3, 0.4], "nodes": [
            {"name": "sun", "rotation_euler_deg": [-45, 30, 0], "components": [{"type": "light", "intensity": 2}]},
            {"name": "sky", "components": [{"type": "light", "kind": "ambient", "intensity": 0.4}]},
            {"name": "model", "components": [{"type": "mesh", "asset": ")" +
                                 asset + R"("}]})" + extra_nodes + "]}";
        return engine::load_scene_text(text, engine::test::source_dir() / "data/scenes/inline.json",
                                       engine.components(), engine.assets());
    }

    // The ground quad (unit, in XZ) turned to face +Z and scaled to 2x2, centred 1 unit above the
    // origin, and a camera 4 units in front of it looking at the origin.
    std::unique_ptr<engine::Scene> facing_quad() {
        auto scene = scene_with((engine::test::repo_dir() / "content/meshes/ground.gltf").string());
        auto& model = *scene->find_node("model");
        model.transform().rotation = glm::quat(glm::radians(glm::vec3(90.0f, 0.0f, 0.0f)));
        model.transform().scale = glm::vec3(2.0f);
        model.transform().translation = glm::vec3(0.0f, 1.0f, 0.0f);
        return scene;
    }
    static engine::CameraView quad_camera(int w, int h) {
        return engine::make_look_at_camera({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), w, h, 0.1f, 100.0f);
    }

    engine::Image render(const engine::Scene& scene, int w, int h) {
        engine::RenderTarget target(w, h);
        engine.renderer().render(scene, engine::framing_camera(scene, w, h, glm::radians(40.0f)), target);
        return target.read_color();
    }
};

}  // namespace

// Golden images of every real model, framed by its bounds. Tolerance: PSNR >= 35 dB and at most
// 0.5% of pixels off by more than 24/255 (rasterisation and texture filtering differ slightly
// between drivers).
TEST_F(MeshPassTest, RealModelsMatchGoldenImages) {
    ENGINE_REQUIRE_SHARED_DATA();
    const std::pair<const char*, const char*> models[] = {
        {"box", "online3dviewer/Box/glTF/Box.gltf"},
        {"box_binary", "online3dviewer/Box/glTF-Binary/Box.glb"},
        {"box_embedded", "online3dviewer/Box/glTF-Embedded/Box.gltf"},
        {"box_textured", "online3dviewer/BoxTextured/glTF-Binary/BoxTextured.glb"},
        {"cube", "tinygltf/Cube/Cube.gltf"},
        {"flight_helmet", "bevy/FlightHelmet/FlightHelmet.gltf"},
        {"fox", "bevy/Fox/Fox.glb"},
    };
    for (const auto& [name, path] : models) {
        SCOPED_TRACE(name);
        const auto scene = scene_with(engine::test::data_file(std::string("gltf/") + path).string());
        EXPECT_TRUE(engine::test::matches_golden(render(*scene, 192, 144), std::string("mesh_") + name));
    }
}

TEST_F(MeshPassTest, ThreeBoxVariantsRenderIdentically) {
    ENGINE_REQUIRE_DATA("gltf/online3dviewer/Box/glTF/Box.gltf");
    ENGINE_REQUIRE_DATA("gltf/online3dviewer/Box/glTF-Binary/Box.glb");
    ENGINE_REQUIRE_DATA("gltf/online3dviewer/Box/glTF-Embedded/Box.gltf");
    const auto dir = engine::test::data_file("gltf/online3dviewer/Box");
    const auto a = render(*scene_with((dir / "glTF/Box.gltf").string()), 96, 72);
    const auto b = render(*scene_with((dir / "glTF-Binary/Box.glb").string()), 96, 72);
    const auto c = render(*scene_with((dir / "glTF-Embedded/Box.gltf").string()), 96, 72);
    EXPECT_EQ(a.rgba, b.rgba);
    EXPECT_EQ(a.rgba, c.rgba);
}

// A ground quad facing the camera at a known distance: colour, depth and orientation.
TEST_F(MeshPassTest, WritesViewDepthAndKeepsTheImageUpright) {
    const auto scene = facing_quad();
    const int w = 64, h = 48;
    const auto camera = quad_camera(w, h);
    engine::RenderTarget target(w, h);
    engine.renderer().render(*scene, camera, target);
    const auto image = target.read_color();
    const auto depth = target.read_view_depth();
    // The quad spans y in [0, 2]: it covers the upper half of the image (row 0 is the top).
    const auto* top = image.pixel(w / 2, h / 4);
    const auto* bottom = image.pixel(w / 2, 3 * h / 4);
    EXPECT_NEAR(depth[static_cast<std::size_t>(h / 4 * w + w / 2)], 4.0f, 1e-3f);
    EXPECT_TRUE(std::isinf(depth[static_cast<std::size_t>(3 * h / 4 * w + w / 2)]));
    // Background is exactly the scene's display-space colour.
    EXPECT_EQ(bottom[0], std::lround(0.2 * 255));
    EXPECT_EQ(bottom[2], std::lround(0.4 * 255));
    EXPECT_GT(top[1], top[2]);  // the green material
}

// Picking meshes (engine/render/picking.h): on every pixel of the quad the renderer's answer, ready with
// the frame, is the mesh node at the depth the mesh pass wrote, its point projecting back to the pixel's
// centre; below the quad it is nothing. A late quad (drawn after the plugins) is picked as well.
TEST_F(MeshPassTest, PickingFindsTheMeshWhereItsDepthIs) {
    for (const bool late : {false, true}) {
        SCOPED_TRACE(late);
        const auto scene = facing_quad();
        scene->find_node("model")->find_component<engine::MeshComponent>()->late = late;
        const int w = 32, h = 24;
        const auto camera = quad_camera(w, h);
        std::vector<std::uint64_t> tickets;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) tickets.push_back(engine.renderer().pick({x, y}));
        EXPECT_FALSE(engine.renderer().pick_result(tickets.front()).ready);
        engine::RenderTarget target(w, h);
        for (std::size_t frame = 0; frame * engine::kMaxPicksPerFrame < tickets.size(); ++frame)
            engine.renderer().render(*scene, camera, target);
        const auto depth = target.read_view_depth();
        std::size_t hits = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t p = static_cast<std::size_t>(y * w + x);
                const engine::PickResult result = engine.renderer().pick_result(tickets[p]);
                ASSERT_TRUE(result.ready);
                ASSERT_EQ(result.hit.has_value(), std::isfinite(depth[p])) << x << ", " << y;
                if (!result.hit) continue;
                ++hits;
                EXPECT_EQ(result.hit->node, scene->find_node("model"));
                EXPECT_NEAR(result.hit->depth, depth[p], 1e-5 * depth[p]);
                const glm::vec3 back = camera.project_to_pixel(glm::vec3(result.hit->position));
                EXPECT_NEAR(back.x, x + 0.5f, 1e-3f);
                EXPECT_NEAR(back.y, y + 0.5f, 1e-3f);
            }
        EXPECT_GT(hits, 80u);  // the quad is about 10 pixels square
    }
}

// Distance fog (engine/render/fog_pass.h) over the same quad at 4 m: its pixels move toward the fog
// colour by 1 − exp(−density · 4) in linear light, the background (no depth) keeps its colour, and
// settings that make no sense are refused.
TEST_F(MeshPassTest, FogMixesByViewDepthAndLeavesTheBackground) {
    const auto scene = facing_quad();
    const int w = 64, h = 48;
    const auto camera = quad_camera(w, h);
    engine::RenderTarget target(w, h);
    engine.renderer().render(*scene, camera, target);
    const auto clear = target.read_color();
    engine::FogSettings fog;
    fog.colour = {1.0f, 1.0f, 1.0f};
    fog.density = 0.25f;
    const auto pass = std::make_shared<engine::FogPass>(fog);
    engine.renderer().add_pass(pass);
    engine.renderer().render(*scene, camera, target);
    const auto foggy = target.read_color();
    const auto linear = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
    const auto encoded = [](double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; };
    const double f = 1.0 - std::exp(-0.25 * 4.0);
    const auto* before = clear.pixel(w / 2, h / 4);
    const auto* after = foggy.pixel(w / 2, h / 4);
    for (int c = 0; c < 3; ++c) {
        const double expected = encoded(linear(before[c] / 255.0) * (1.0 - f) + f) * 255.0;
        EXPECT_NEAR(after[c], expected, 1.0) << "channel " << c;
    }
    for (int c = 0; c < 4; ++c) EXPECT_EQ(foggy.pixel(w / 2, 3 * h / 4)[c], clear.pixel(w / 2, 3 * h / 4)[c]);
    pass->settings.density = -1.0f;
    EXPECT_THROW(engine.renderer().render(*scene, camera, target), engine::Error);
    EXPECT_NE(engine::check_fog(pass->settings).find("density"), std::string::npos);
    engine.renderer().remove_pass("fog");
}

TEST_F(MeshPassTest, PublishesFrameStatisticsWithGpuTimesLater) {
    const auto ground = (engine::test::repo_dir() / "content/meshes/ground.gltf").string();
    const auto scene = scene_with(ground);
    std::vector<plugin_msgs::FrameStatistics> seen;
    auto subscription = engine.bus().subscribe<plugin_msgs::FrameStatistics>([&](const auto& s) { seen.push_back(s); });
    engine::RenderTarget target(32, 32);
    const auto camera = engine::framing_camera(*scene, 32, 32, 1.0f);
    // Timer results are read without waiting: they arrive a few frames late (bounded here).
    int frames = 0;
    while (frames < 200 && (seen.empty() || seen.back().gpu_frame_index < 0)) {
        engine.renderer().render(*scene, camera, target);
        ++frames;
    }
    ASSERT_EQ(seen.size(), static_cast<std::size_t>(frames));
    ASSERT_GE(frames, 2);
    // However busy the machine, results arrive once max_frames_in_flight frames are outstanding.
    EXPECT_LE(frames, static_cast<int>(engine::gl::GpuTimers::max_frames_in_flight) + 2);
    EXPECT_EQ(seen.front().passes.at(0).name, "mesh");
    EXPECT_GE(seen.back().passes.at(0).cpu_ms, 0.0);
    EXPECT_GE(seen.back().gpu_frame_index, 0);
    EXPECT_LT(seen.back().gpu_frame_index, static_cast<std::int64_t>(seen.back().frame_index));
    EXPECT_GE(seen.back().passes.at(0).gpu_ms, 0.0);
}
