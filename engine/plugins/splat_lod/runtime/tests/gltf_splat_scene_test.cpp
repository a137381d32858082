// A .glb holding triangles and KHR_gaussian_splatting primitives together, named by one "mesh"
// component: the mesh pass draws the triangles, the plugin's companion puts the splats beside them,
// and the two composite by depth (docs/algorithms.md §1) like any mesh and splat component.
#include <cmath>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "engine/core/file_io.h"
#include "engine/engine.h"
#include "engine/render/render_target.h"
#include "engine/render/scene_camera.h"
#include "gltf_splats_test_helpers.h"
#include "gpu_fixture.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "splat_test_data.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace ref = splat_lod::reference;

namespace {

// A ball of Gaussians of radius 0.5 around (0.6, 0, 0), coloured by height.
splat_lod::SplatCloud ball() {
    std::vector<engine::test::GaussianSpec> specs;
    std::mt19937 rng(7);
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (int i = 0; i < 600; ++i) {
        glm::vec3 p(n(rng), n(rng), n(rng));
        p = 0.5f * glm::normalize(p) * std::cbrt(std::uniform_real_distribution<float>(0.0f, 1.0f)(rng));
        specs.push_back(
            {p + glm::vec3(0.6f, 0.0f, 0.0f), glm::vec3(-3.2f), {1, 0, 0, 0}, 1.5f, {0.9f, 0.5f + p.y, 0.2f}});
    }
    return engine::test::make_cloud(specs);
}

// The project's splat glTF with a second node: a 1.4 m square quad in the plane z = 0 whose edge
// x = 0.7 cuts the ball: the ball's front half covers the quad, the quad hides its back half except
// beyond that edge.
nlohmann::json mesh_and_splats(const splat_lod::SplatCloud& cloud) {
    const auto text = splat_lod::encode_gltf_splats(cloud, false);
    nlohmann::json doc = nlohmann::json::parse(text.begin(), text.end());
    const float s = 0.7f;
    const float positions[] = {-s, -s, 0, s, -s, 0, s, s, 0, -s, s, 0};
    const std::uint16_t indices[] = {0, 1, 2, 0, 2, 3};
    std::vector<std::uint8_t> bytes(sizeof(positions) + sizeof(indices));
    std::memcpy(bytes.data(), positions, sizeof(positions));
    std::memcpy(bytes.data() + sizeof(positions), indices, sizeof(indices));
    const auto buffer = doc["buffers"].size(), view = doc["bufferViews"].size(), accessor = doc["accessors"].size();
    doc["buffers"].push_back(
        {{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + gltf_test::base64(bytes)}});
    doc["bufferViews"].push_back({{"buffer", buffer}, {"byteOffset", 0}, {"byteLength", sizeof(positions)}});
    doc["bufferViews"].push_back(
        {{"buffer", buffer}, {"byteOffset", sizeof(positions)}, {"byteLength", sizeof(indices)}});
    doc["accessors"].push_back({{"bufferView", view},
                                {"componentType", 5126},
                                {"count", 4},
                                {"type", "VEC3"},
                                {"min", {-s, -s, 0}},
                                {"max", {s, s, 0}}});
    doc["accessors"].push_back({{"bufferView", view + 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}});
    doc["meshes"].push_back(
        {{"name", "quad"}, {"primitives", {{{"attributes", {{"POSITION", accessor}}}, {"indices", accessor + 1}}}}});
    doc["nodes"].push_back({{"mesh", doc["meshes"].size() - 1}});
    doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
    return doc;
}

// A binary glTF holding `doc` as its JSON chunk (its buffers stay data URIs, which a .glb may have).
std::vector<std::uint8_t> glb_of(const nlohmann::json& doc) {
    std::string json = doc.dump();
    json.resize((json.size() + 3) / 4 * 4, ' ');
    const auto u32 = [](std::vector<std::uint8_t>& out, std::uint32_t v) {
        for (int k = 0; k < 4; ++k) out.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
    };
    std::vector<std::uint8_t> out = {'g', 'l', 'T', 'F'};
    u32(out, 2);
    u32(out, static_cast<std::uint32_t>(12 + 8 + json.size()));
    u32(out, static_cast<std::uint32_t>(json.size()));
    u32(out, 0x4E4F534Au);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    return out;
}

}  // namespace

TEST(GltfSplatScene, OneMeshComponentDrawsTheTrianglesAndTheSplatsCompositedByDepth) {
    const auto dir = engine::test::output_dir("gltf_splat_scene");
    const splat_lod::SplatCloud cloud = ball();
    engine::write_file_atomic(dir / "quad_and_ball.glb", glb_of(mesh_and_splats(cloud)));
    engine::write_text_file_atomic(dir / "scene.json", R"({"background": [0.2, 0.25, 0.3], "nodes": [
        {"name": "camera", "translation": [1.2, 0.8, 2.2], "look_at": [0, 0, 0],
         "components": [{"type": "camera", "fov_y_deg": 45}]},
        {"name": "sun", "rotation_euler_deg": [-40, 30, 0], "components": [{"type": "light", "intensity": 2.0}]},
        {"name": "model", "translation": [0, 0.1, 0], "components": [{"type": "mesh", "asset": "quad_and_ball.glb"}]}]})");
    engine::test::gl_context().make_current();
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    const auto scene = engine.load_scene(dir / "scene.json");
    auto* model = scene->find_node("model");
    ASSERT_EQ(model->components().size(), 2u) << "the mesh and, beside it, its splats";
    auto* splats = model->find_component<splat_lod::SplatComponent>();
    ASSERT_NE(splats, nullptr);
    ASSERT_EQ(splats->cloud->size(), cloud.size());

    const int w = 160, h = 120;
    const auto camera = *engine::scene_camera(*scene, "", w, h);
    engine::RenderTarget target(w, h);
    splat_lod::render_complete(engine, *scene, camera, target);
    const engine::Image gpu = target.read_color();

    // The reference: the CPU renderer composited over the GPU's mesh layer (the scene without splats).
    const auto kept = splats->cloud;
    splats->cloud = std::make_shared<const splat_lod::SplatCloud>();
    engine.renderer().render(*scene, camera, target);
    const engine::Image mesh_colour = target.read_color();
    const ref::MeshLayer layer = engine::test::mesh_layer(target);
    const ref::ReferenceInstance instance{kept.get(), glm::dmat4(model->world_matrix()), splat_lod::kMaxShDegree};
    const auto cpu =
        ref::to_image8(ref::render_reference(std::span(&instance, 1), camera, ref::ReferenceSettings{}, &layer));
    EXPECT_GE(engine::compare_images(gpu, cpu).psnr_db, 40.0);
    EXPECT_GT(engine::compare_images(gpu, mesh_colour).fraction_over_threshold, 0.05) << "the splats show";
    EXPECT_TRUE(engine::test::matches_golden(gpu, "gltf_mesh_and_splats"));
}

// The same Gaussians render the same from the PLY they came from and from KHR_gaussian_splatting glTF:
// float attributes (the project's writer), quantised ones (normalized signed-short rotations and
// unsigned-short opacities: within their step) and the SPZ-compressed primitive (against the same SPZ
// stream read as a file, turned by the half-turn about y that the glTF variant's axes differ by).
TEST(GltfSplatScene, TheSameGaussiansRenderTheSameFromPlyAndGltf) {
    engine::test::gl_context().make_current();
    engine::test::SplatRenderHarness harness;
    ENGINE_REQUIRE_DATA("splats/playcanvas-engine/guitar.compressed.ply");
    const auto guitar = engine::test::data_file("splats/playcanvas-engine/guitar.compressed.ply");
    const auto ply = std::make_shared<const splat_lod::SplatCloud>(splat_lod::load_splat_file(guitar));
    const auto camera = engine::test::orbit_cameras(*ply, {0, -1, 0}, 1, 256, 192).front();
    const engine::Image from_ply = harness.render({ply}, camera);

    const auto dir = engine::test::output_dir("gltf_splat_scene");
    splat_lod::write_gltf_splats(dir / "guitar.glb", *ply);
    const auto glb = std::make_shared<const splat_lod::SplatCloud>(splat_lod::load_splat_file(dir / "guitar.glb"));
    const double float_db = engine::compare_images(harness.render({glb}, camera), from_ply).psnr_db;
    EXPECT_GE(float_db, 60.0) << "float attributes";
    RecordProperty("float_psnr_db", std::to_string(float_db));

    gltf_test::Builder quantised;
    quantised.primitive(*ply, {{gltf_test::kShort, true}, {gltf_test::kFloat, false}, {gltf_test::kUShort, true}});
    const auto bytes = quantised.file();
    const auto q = std::make_shared<const splat_lod::SplatCloud>(splat_lod::read_gltf_splats(bytes, "guitar_q.gltf"));
    const double quantised_db = engine::compare_images(harness.render({q}, camera), from_ply).psnr_db;
    EXPECT_GE(quantised_db, 50.0) << "16-bit quantised";
    RecordProperty("quantised_psnr_db", std::to_string(quantised_db));

    const auto spz = splat_io_test::encode_spz(*ply, 2);
    const auto spz_cloud = std::make_shared<const splat_lod::SplatCloud>(splat_lod::read_spz(spz, "guitar.spz"));
    gltf_test::Builder compressed;
    compressed.bytes = spz;
    compressed.doc["bufferViews"].push_back({{"buffer", 0}, {"byteLength", spz.size()}});
    compressed.doc["accessors"].push_back({{"componentType", 5126}, {"count", ply->size()}, {"type", "VEC3"}});
    const nlohmann::json spz_extension = {{"KHR_gaussian_splatting_compression_spz_2", {{"bufferView", 0}}}};
    compressed.doc["meshes"][0]["primitives"].push_back(
        {{"attributes", {{"POSITION", 0}}},
         {"mode", 0},
         {"extensions", {{"KHR_gaussian_splatting", {{"kernel", "ellipse"}, {"extensions", spz_extension}}}}}});
    const auto spz_bytes = compressed.file();
    const auto from_gltf =
        std::make_shared<const splat_lod::SplatCloud>(splat_lod::read_gltf_splats(spz_bytes, "guitar_spz.gltf"));
    const glm::mat4 half_turn = glm::rotate(glm::mat4(1.0f), glm::radians(180.0f), glm::vec3(0, 1, 0));
    const engine::Image spz_file = harness.render({spz_cloud}, camera, {}, {half_turn});
    const double spz_db = engine::compare_images(harness.render({from_gltf}, camera), spz_file).psnr_db;
    EXPECT_GE(spz_db, 60.0) << "SPZ-compressed primitive";
    RecordProperty("spz_psnr_db", std::to_string(spz_db));
    // Against the PLY itself, through SPZ's own quantisation (12 fractional bits of position, 8-bit scales,
    // rotations and colours).
    const double spz_vs_ply =
        engine::compare_images(harness.render({from_gltf}, camera, {}, {half_turn}), from_ply).psnr_db;
    EXPECT_GE(spz_vs_ply, 60.0);
    RecordProperty("spz_vs_ply_psnr_db", std::to_string(spz_vs_ply));
}
