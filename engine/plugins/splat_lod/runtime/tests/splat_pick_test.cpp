// Picking (docs/picking.md): the splats' answer against the double-precision CPU reference's median
// depth on the real scenes, the component and node named, nothing where nothing is drawn, the scene's
// answer (meshes and splats) against the frame's own view depth, and answers that never hold up a frame.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/gl/compute_step.h"
#include "engine/render/picking.h"
#include "engine/render/render_target.h"
#include "engine/render/renderer.h"
#include "engine/render/scene_camera.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_loader.h"
#include "gpu_fixture.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace ref = splat_lod::reference;

namespace {

class SplatPickTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness harness;
    splat_lod::SplatRenderer pass{harness.engine().renderer()};
    engine::Renderer& renderer() { return harness.engine().renderer(); }

    // A scene of one splat component per cloud, on nodes "splats 0", "splats 1", … at `translations`.
    static std::unique_ptr<engine::Scene> splat_scene(
        const std::vector<std::shared_ptr<const splat_lod::SplatCloud>>& clouds,
        const std::vector<glm::vec3>& translations) {
        auto scene = std::make_unique<engine::Scene>();
        for (std::size_t i = 0; i < clouds.size(); ++i) {
            auto component = std::make_unique<splat_lod::SplatComponent>();
            component->cloud = clouds[i];
            engine::Node& node = scene->root().add_child("splats " + std::to_string(i));
            if (i < translations.size()) node.transform().translation = translations[i];
            node.attach(std::move(component));
        }
        return scene;
    }
};

std::vector<glm::ivec2> random_pixels(int count, int width, int height, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> x(0, width - 1), y(0, height - 1);
    std::vector<glm::ivec2> pixels;
    for (int i = 0; i < count; ++i) pixels.emplace_back(x(rng), y(rng));
    return pixels;
}

std::size_t index_of(glm::ivec2 p, int width) {
    return static_cast<std::size_t>(p.y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(p.x);
}

}  // namespace

// Done-when of picking: on 100 random pixels of every real scene, and 100 more where the reference reaches
// a half, the picked point is within one pixel's footprint (its depth over the focal length) of the
// reference's point at its median depth, the node is the cloud's, and a pixel where the reference's
// opacity never reaches ½ picks nothing.
TEST_F(SplatPickTest, RealScenesPickWhereTheReferenceReachesAHalf) {
    ENGINE_REQUIRE_SHARED_DATA();
    for (const auto& real : engine::test::real_splat_scenes()) {
        SCOPED_TRACE(real.name);
        const auto cloud = std::make_shared<const splat_lod::SplatCloud>(splat_lod::load_splat_file(real.path));
        const auto camera = engine::test::orbit_cameras(*cloud, real.up, 1, 200, 150).front();
        const auto scene = splat_scene({cloud}, {});
        const ref::ReferenceInstance instance{cloud.get(), glm::dmat4(1.0), splat_lod::kMaxShDegree};
        const ref::ReferenceImage cpu = ref::render_reference(std::span(&instance, 1), camera, {});
        // 100 pixels anywhere in the image and 100 among those where the reference reaches a half.
        std::vector<glm::ivec2> pixels = random_pixels(100, camera.width, camera.height, 7);
        std::vector<glm::ivec2> on_cloud;
        for (const glm::ivec2 p : random_pixels(20000, camera.width, camera.height, 8))
            if (on_cloud.size() < 100 && std::isfinite(cpu.depth_median[index_of(p, camera.width)]))
                on_cloud.push_back(p);
        ASSERT_EQ(on_cloud.size(), 100u);
        pixels.insert(pixels.end(), on_cloud.begin(), on_cloud.end());
        std::vector<std::uint64_t> tickets;
        for (const glm::ivec2 p : pixels) tickets.push_back(pass.pick(p));
        engine::RenderTarget target(camera.width, camera.height);
        for (std::size_t drawn = 0; drawn < pixels.size(); drawn += engine::kMaxPicksPerFrame)
            splat_lod::render_complete(harness.engine(), *scene, camera, target);

        const double focal = camera.focal_length();
        std::size_t hits = 0, within = 0, one_sided = 0;
        double worst = 0.0;
        for (std::size_t k = 0; k < pixels.size(); ++k) {
            const engine::PickResult result = pass.pick_result(tickets[k], true);
            ASSERT_TRUE(result.ready);
            const double depth = cpu.depth_median[index_of(pixels[k], camera.width)];
            if (std::isfinite(depth) != result.hit.has_value()) ++one_sided;
            if (!std::isfinite(depth) || !result.hit) continue;
            ++hits;
            EXPECT_EQ(result.hit->node, scene->find_node("splats 0"));
            const glm::dvec3 expected = engine::pixel_ray_point(camera, pixels[k], depth);
            const double off = glm::length(result.hit->position - expected) / (depth / focal);
            worst = std::max(worst, off);
            within += off <= 1.0 ? 1 : 0;
        }
        EXPECT_GE(hits, 100u);
        EXPECT_EQ(within, hits) << "picked points within a pixel's footprint of the reference's";
        EXPECT_EQ(one_sided, 0u) << "pixels where only one side reaches a half";
        RecordProperty(real.name + "_worst_in_footprints", std::to_string(worst));
        RecordProperty(real.name + "_hits", std::to_string(hits));
    }
}

// Two clouds side by side: a pixel on each names its node and component, with and without a splat budget
// that binds (under a budget the trim, not the projection, leaves the instance in the projected splat); a
// pixel between them, and one in a corner, pick nothing.
TEST_F(SplatPickTest, ThePickNamesTheComponentAndNodeHit) {
    std::vector<engine::test::GaussianSpec> specs;
    for (int i = 0; i < 27; ++i)
        specs.push_back({glm::vec3(i % 3, (i / 3) % 3, i / 9) * 0.15f - 0.15f,
                         glm::vec3(-2.5f + 0.02f * static_cast<float>(i)),
                         {1, 0, 0, 0},
                         4.0f,
                         glm::vec3(0.8f, 0.3f, 0.2f)});
    const auto cloud = std::make_shared<const splat_lod::SplatCloud>(engine::test::make_cloud(specs));
    const auto scene = splat_scene({cloud, cloud}, {glm::vec3(-1.0f, 0.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f)});
    const auto camera = engine::make_look_at_camera({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 0.8f, 160, 120, 0.1f, 100.0f);
    const glm::vec3 left = camera.project_to_pixel({-1, 0, 0}), right = camera.project_to_pixel({1, 0, 0});
    for (const std::uint32_t budget : {0u, 40u}) {
        SCOPED_TRACE(budget);
        harness.edit_lod([&](plugin_msgs::LodSettings& lod) { lod.splat_budget = budget; });
        const std::uint64_t a = pass.pick(glm::ivec2(left)), b = pass.pick(glm::ivec2(right));
        const std::uint64_t between = pass.pick({80, 60}), corner = pass.pick({0, 0});
        engine::RenderTarget target(camera.width, camera.height);
        splat_lod::render_complete(harness.engine(), *scene, camera, target);
        if (budget > 0) {
            EXPECT_LE(pass.latest_statistics()->visible, budget);
            EXPECT_GT(pass.latest_statistics()->unbudgeted, budget);  // it binds
        }
        const engine::PickResult on_left = pass.pick_result(a, true), on_right = pass.pick_result(b, true);
        ASSERT_TRUE(on_left.hit && on_right.hit);
        EXPECT_EQ(on_left.hit->node, scene->find_node("splats 0"));
        EXPECT_EQ(on_right.hit->node, scene->find_node("splats 1"));
        EXPECT_EQ(on_right.hit->component, scene->find_node("splats 1")->find_component<splat_lod::SplatComponent>());
        // The front of the cube of Gaussians is at z = 0.15 (its nearest layer, also the largest Gaussians,
        // which the budget keeps), 3.85 from the camera.
        EXPECT_NEAR(on_left.hit->depth, 3.85, 0.15);
        EXPECT_NEAR(on_left.hit->position.x, -1.0, 0.05);
        EXPECT_FALSE(pass.pick_result(between, true).hit);
        EXPECT_FALSE(pass.pick_result(corner, true).hit);
    }
    harness.edit_lod([](plugin_msgs::LodSettings& lod) { lod.splat_budget = 0; });
}

// The scene's pick (engine::Renderer::pick: the meshes' ray cast and the splats' answer, the nearer
// wins) lands on the frame's own view depth, the nearer of the meshes and the splats' median, on 100
// random pixels of biker_with_boxes; the node is a mesh's where the meshes' depth is the nearer.
TEST_F(SplatPickTest, TheScenePickIsTheNearestSurfaceOfTheFrame) {
    auto& engine = harness.engine();
    const auto scene = engine.load_scene(engine::test::repo_dir() / "content/scenes/biker_with_boxes.json");
    const int w = 192, h = 144;
    const auto camera = *engine::scene_camera(*scene, "", w, h);
    const std::vector<glm::ivec2> pixels = random_pixels(100, w, h, 11);
    std::vector<std::uint64_t> tickets;
    for (const glm::ivec2 p : pixels) tickets.push_back(renderer().pick(p));
    engine::RenderTarget target(w, h);
    for (std::size_t drawn = 0; drawn < pixels.size(); drawn += engine::kMaxPicksPerFrame)
        splat_lod::render_complete(engine, *scene, camera, target);
    const std::vector<float> view_depth = target.read_view_depth();
    const engine::Node* biker = scene->find_node("biker");
    std::size_t on_meshes = 0, on_splats = 0, nothing = 0;
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        SCOPED_TRACE(k);
        const engine::PickResult result = renderer().pick_result(tickets[k], true);
        const float depth = view_depth[index_of(pixels[k], w)];
        ASSERT_EQ(result.hit.has_value(), std::isfinite(depth));
        if (!result.hit) {
            ++nothing;
            continue;
        }
        EXPECT_NEAR(result.hit->depth, depth, 1e-4 * depth);
        (result.hit->node == biker ? on_splats : on_meshes) += 1;
    }
    EXPECT_GT(on_meshes, 10u);
    EXPECT_GT(on_splats, 3u);
    EXPECT_GT(nothing, 10u);
}

// Answers come back without holding up a frame: after the frame that draws the pixel one readback is in
// flight, the next frame does not read it, asking without `wait` does not wait for it (not ready, or
// ready once the GPU is done), and after the GPU finishes it is read without waiting.
TEST_F(SplatPickTest, AnswersNeverBlockTheNextFrame) {
    std::vector<engine::test::GaussianSpec> specs(1, {glm::vec3(0.0f), glm::vec3(-1.0f), {1, 0, 0, 0}, 4.0f});
    const auto cloud = std::make_shared<const splat_lod::SplatCloud>(engine::test::make_cloud(specs));
    const auto scene = splat_scene({cloud}, {});
    const auto camera = engine::make_look_at_camera({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 0.8f, 64, 48, 0.1f, 100.0f);
    engine::RenderTarget target(camera.width, camera.height);
    const std::uint64_t ticket = pass.pick({32, 24});
    EXPECT_FALSE(pass.pick_result(ticket).ready);  // not drawn yet
    EXPECT_THROW(pass.pick_result(ticket, true), engine::Error);
    EXPECT_EQ(pass.picks_in_flight(), 0u);
    renderer().render(*scene, camera, target);
    EXPECT_EQ(pass.picks_in_flight(), 1u);
    renderer().render(*scene, camera, target);  // the next frame leaves it to the caller
    EXPECT_EQ(pass.picks_in_flight(), 1u);
    for (int frame = 0; frame < 3; ++frame) {
        const engine::PickResult polled = pass.pick_result(ticket);
        EXPECT_EQ(pass.picks_in_flight(), polled.ready ? 0u : 1u);
        if (polled.ready) break;
        renderer().render(*scene, camera, target);
    }
    engine::gl::finish();
    const engine::PickResult result = pass.pick_result(ticket);
    EXPECT_TRUE(result.ready);
    EXPECT_EQ(pass.picks_in_flight(), 0u);
    ASSERT_TRUE(result.hit);
    EXPECT_NEAR(result.hit->depth, 4.0, 0.5);
}
