#include <fstream>

#include <gtest/gtest.h>

#include "engine/assets/mesh_asset.h"
#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "test_support.h"

namespace {

std::filesystem::path gltf(const std::string& relative) {
    return engine::test::data_file("gltf/" + relative);
}

std::string load_error(const std::filesystem::path& path) {
    try {
        engine::load_gltf(path);
    } catch (const engine::Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST(GltfLoader, LoadsTheRealModels) {
    ENGINE_REQUIRE_SHARED_DATA();
    struct Case {
        const char* path;
        std::size_t triangles;
        std::size_t images;
    };
    const Case cases[] = {
        {"online3dviewer/Box/glTF/Box.gltf", 12, 0},
        {"online3dviewer/Box/glTF-Binary/Box.glb", 12, 0},
        {"online3dviewer/Box/glTF-Embedded/Box.gltf", 12, 0},
        {"online3dviewer/BoxTextured/glTF/BoxTextured.gltf", 12, 1},
        {"online3dviewer/BoxTextured/glTF-Binary/BoxTextured.glb", 12, 1},
        {"online3dviewer/BoxTextured/glTF-Embedded/BoxTextured.gltf", 12, 1},
        {"tinygltf/Cube/Cube.gltf", 12, 2},
        {"bevy/FlightHelmet/FlightHelmet.gltf", 94722, 15},
        {"bevy/Fox/Fox.glb", 576, 1},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.path);
        const auto asset = engine::load_gltf(gltf(c.path));
        EXPECT_EQ(asset.triangle_count(), c.triangles);
        EXPECT_EQ(asset.images.size(), c.images);
        for (const auto& image : asset.images)
            EXPECT_EQ(image.rgba.size(), std::size_t(image.width) * image.height * 4);
        EXPECT_LT(asset.bounds_min.x, asset.bounds_max.x);
        for (const auto& p : asset.primitives)
            for (const auto& v : p.vertices) ASSERT_NEAR(glm::length(v.normal), 1.0f, 0.02f);
    }
}

TEST(GltfLoader, BoxVariantsAgree) {
    ENGINE_REQUIRE_DATA("gltf/online3dviewer/Box/glTF/Box.gltf");
    ENGINE_REQUIRE_DATA("gltf/online3dviewer/Box/glTF-Binary/Box.glb");
    const auto a = engine::load_gltf(gltf("online3dviewer/Box/glTF/Box.gltf"));
    const auto b = engine::load_gltf(gltf("online3dviewer/Box/glTF-Binary/Box.glb"));
    ASSERT_EQ(a.primitives.size(), b.primitives.size());
    EXPECT_EQ(a.primitives[0].indices, b.primitives[0].indices);
    EXPECT_EQ(a.bounds_min, b.bounds_min);
    // The Box's node turns Z-up into Y-up: the transform is applied to the bounds.
    EXPECT_NEAR(a.bounds_max.y - a.bounds_min.y, 1.0f, 1e-5f);
    EXPECT_NEAR(a.materials.at(0).base_color_factor.x, 0.8f, 1e-5f);
}

TEST(GltfLoader, DracoIsAnUnsupportedRequiredExtension) {
    ENGINE_REQUIRE_DATA("gltf/online3dviewer/Box/glTF-Draco/Box.gltf");
    const std::string e = load_error(gltf("online3dviewer/Box/glTF-Draco/Box.gltf"));
    EXPECT_NE(e.find("Box.gltf: unsupported required extension KHR_draco_mesh_compression"), std::string::npos) << e;
}

TEST(GltfLoader, MissingFileAndWrongExtension) {
    EXPECT_NE(load_error("/nonexistent/model.gltf").find("/nonexistent/model.gltf: file not found"), std::string::npos);
    const auto dir = engine::test::output_dir("gltf_loader");
    engine::write_text_file_atomic(dir / "model.obj", "o cube\n");
    EXPECT_NE(load_error(dir / "model.obj").find("not a glTF file"), std::string::npos);
}

TEST(GltfLoader, TruncatedGlbIsAClearError) {
    ENGINE_REQUIRE_DATA("gltf/online3dviewer/BoxTextured/glTF-Binary/BoxTextured.glb");
    const auto bytes = engine::read_binary_file(gltf("online3dviewer/BoxTextured/glTF-Binary/BoxTextured.glb"));
    const auto dir = engine::test::output_dir("gltf_loader");
    for (std::size_t keep :
         {std::size_t{0}, std::size_t{11}, std::size_t{20}, std::size_t{100}, bytes.size() / 2, bytes.size() - 1}) {
        SCOPED_TRACE(keep);
        const auto path = dir / ("truncated_" + std::to_string(keep) + ".glb");
        engine::write_file_atomic(path, std::span(bytes.data(), keep));
        const std::string e = load_error(path);
        EXPECT_NE(e.find(path.string()), std::string::npos) << e;
        EXPECT_EQ(e.find("(no error)"), std::string::npos);
    }
}

TEST(GltfLoader, CorruptJsonAndMissingTexture) {
    ENGINE_REQUIRE_DATA("gltf/online3dviewer/BoxTextured/glTF/BoxTextured.gltf");
    ENGINE_REQUIRE_DATA("gltf/online3dviewer/BoxTextured/glTF/BoxTextured0.bin");
    const auto dir = engine::test::output_dir("gltf_loader");
    engine::write_text_file_atomic(dir / "corrupt.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [");
    EXPECT_NE(load_error(dir / "corrupt.gltf").find("corrupt.gltf: cannot load glTF"), std::string::npos);

    // BoxTextured with its .bin beside it but without the PNG it names.
    const auto src = gltf("online3dviewer/BoxTextured/glTF");
    std::filesystem::copy_file(src / "BoxTextured.gltf", dir / "BoxTextured.gltf",
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(src / "BoxTextured0.bin", dir / "BoxTextured0.bin",
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::remove(dir / "CesiumLogoFlat.png");
    const std::string e = load_error(dir / "BoxTextured.gltf");
    EXPECT_NE(e.find("BoxTextured.gltf"), std::string::npos) << e;
    EXPECT_NE(e.find("CesiumLogoFlat.png"), std::string::npos) << e;
}

TEST(GltfLoader, HostileAccessorsAreRejected) {
    const auto dir = engine::test::output_dir("gltf_loader");
    // One triangle whose accessor claims more vertices than its 36-byte buffer holds.
    const std::string doc = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
      "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
      "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],
      "accessors":[{"bufferView":0,"componentType":5126,"count":1000000,"type":"VEC3"}]})";
    engine::write_text_file_atomic(dir / "hostile.gltf", doc);
    const std::string e = load_error(dir / "hostile.gltf");
    EXPECT_NE(e.find("hostile.gltf"), std::string::npos) << e;
    EXPECT_EQ(e.find("(no error)"), std::string::npos) << e;
}

// Primitives with KHR_gaussian_splatting are the splat plugin's: the mesh loader counts and skips them,
// also when the file requires the extension, and a file of splats alone loads with no triangles.
TEST(GltfLoader, SplatPrimitivesAreSkippedAndCounted) {
    const auto dir = engine::test::output_dir("gltf_loader");
    // A triangle (3 vertices) and a splat primitive reading the same POSITION accessor.
    const std::string buffer =
        R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
      "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],
      "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}])";
    const std::string splat = R"({"mode":0,"attributes":{"POSITION":0},"extensions":{"KHR_gaussian_splatting":{}}})";
    const auto write = [&](const std::string& name, const std::string& primitives) {
        engine::write_text_file_atomic(dir / name,
                                       R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_gaussian_splatting"],
              "extensionsRequired":["KHR_gaussian_splatting"],"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
              "meshes":[{"primitives":[)" + primitives +
                                           "]}]," + buffer + "}");
        return dir / name;
    };
    const auto both = engine::load_gltf(write("mesh_and_splats.gltf", R"({"attributes":{"POSITION":0}},)" + splat));
    EXPECT_EQ(both.primitives.size(), 1u);
    EXPECT_EQ(both.triangle_count(), 1u);
    EXPECT_EQ(both.splat_primitives, 1u);
    const auto only = engine::load_gltf(write("splats_only.gltf", splat));
    EXPECT_TRUE(only.primitives.empty());
    EXPECT_EQ(only.splat_primitives, 1u);
}
