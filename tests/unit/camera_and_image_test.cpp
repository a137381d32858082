#include <limits>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "test_support.h"

TEST(Camera, PixelConventionsAreTheDocumentedOnes) {
    const auto cam =
        engine::make_look_at_camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, glm::radians(90.0f), 200, 100, 0.1f, 100.0f);
    EXPECT_FLOAT_EQ(cam.focal_length(), 50.0f);  // (H/2)/tan(45°)
    const glm::vec3 centre = cam.project_to_pixel({0, 0, 0});
    EXPECT_NEAR(centre.x, 100.0f, 1e-4f);
    EXPECT_NEAR(centre.y, 50.0f, 1e-4f);
    EXPECT_NEAR(centre.z, 5.0f, 1e-5f);
    const glm::vec3 up = cam.project_to_pixel({0, 1, 0});
    EXPECT_LT(up.y, centre.y);  // up in the world is higher (smaller row) in the image
    const glm::vec3 right = cam.project_to_pixel({1, 0, 0});
    EXPECT_NEAR(right.x, 110.0f, 1e-4f);
}

TEST(Camera, ATileViewPutsEveryPointWhereTheWholeImageHasIt) {
    const auto whole =
        engine::make_look_at_camera({1, 2, 5}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), 300, 120, 0.1f, 100.0f);
    EXPECT_FLOAT_EQ(whole.aspect(), 2.5f);
    const glm::ivec2 origin{200, 40};
    const auto tile = engine::tile_view(whole, origin, {100, 50});
    EXPECT_EQ(tile.width, 100);
    EXPECT_EQ(tile.full_size, glm::ivec2(300, 120));
    EXPECT_FLOAT_EQ(tile.focal_length(), whole.focal_length());
    EXPECT_FLOAT_EQ(tile.aspect(), whole.aspect());
    EXPECT_EQ(tile.principal_point(), glm::vec2(150.0f - 200.0f, 60.0f - 40.0f));
    const auto nested = engine::tile_view(tile, {10, 5}, {20, 20});
    EXPECT_EQ(nested.tile_origin, glm::ivec2(210, 45));
    for (const glm::vec3 point : {glm::vec3(0.0f), glm::vec3(1.5f, -0.3f, 0.2f), glm::vec3(-0.7f, 0.9f, -1.0f)}) {
        // The pixel model (project_to_pixel) and the projection matrix (what the mesh pass
        // rasterises) agree with the whole image's, shifted by the tile's origin.
        const glm::vec3 in_whole = whole.project_to_pixel(point), in_tile = tile.project_to_pixel(point);
        EXPECT_NEAR(in_tile.x, in_whole.x - 200.0f, 1e-3f);
        EXPECT_NEAR(in_tile.y, in_whole.y - 40.0f, 1e-3f);
        for (const engine::CameraView* view : {&whole, &tile}) {
            const glm::vec4 clip = view->projection * view->view * glm::vec4(point, 1.0f);
            const glm::vec2 ndc = glm::vec2(clip) / clip.w;
            const glm::vec2 pixel{(ndc.x + 1.0f) * 0.5f * static_cast<float>(view->width),
                                  (1.0f - ndc.y) * 0.5f * static_cast<float>(view->height)};
            const glm::vec3 expected = view->project_to_pixel(point);
            EXPECT_NEAR(pixel.x, expected.x, 2e-3f);
            EXPECT_NEAR(pixel.y, expected.y, 2e-3f);
        }
    }
    EXPECT_THROW(engine::tile_view(whole, {250, 0}, {100, 50}), engine::Error);
    EXPECT_THROW(engine::tile_view(whole, {0, 0}, {0, 50}), engine::Error);
}

// A stereo pair: eyes ipd apart along the centre's right axis, looking the same way, the centre's view
// selecting for both; a point on the centre's axis at depth z appears f·ipd/(2z) pixels right of the
// centre in the left eye and as far left in the right one, at the same row and depth.
TEST(Camera, StereoEyesAreParallelAndShareTheCentresSelection) {
    const auto centre = engine::make_look_at_camera({1, 2, 3}, {1, 2, -7}, {0, 1, 0}, 0.9f, 200, 100, 0.1f, 100.0f);
    const float ipd = 0.064f;
    const engine::StereoEyes eyes = engine::stereo_eyes(centre, ipd);
    EXPECT_NEAR(glm::length(eyes.left.position - glm::vec3(1.0f - ipd / 2, 2, 3)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(eyes.right.position - glm::vec3(1.0f + ipd / 2, 2, 3)), 0.0f, 1e-6f);
    ASSERT_TRUE(eyes.left.selection_view && eyes.right.selection_view);
    EXPECT_EQ(*eyes.left.selection_view, centre.view);
    EXPECT_EQ(*eyes.right.selection_view, centre.view);
    EXPECT_FALSE(centre.selection_view);
    EXPECT_EQ(eyes.left.projection, centre.projection);
    const float z = 4.0f;
    const glm::vec3 c = centre.project_to_pixel({1, 2, 3 - z});
    const glm::vec3 l = eyes.left.project_to_pixel({1, 2, 3 - z}), r = eyes.right.project_to_pixel({1, 2, 3 - z});
    const float shift = centre.focal_length() * ipd / (2.0f * z);
    EXPECT_NEAR(l.x - c.x, shift, 1e-3f);
    EXPECT_NEAR(c.x - r.x, shift, 1e-3f);
    EXPECT_NEAR(l.y, c.y, 1e-4f);
    EXPECT_NEAR(l.z, z, 1e-5f);
    EXPECT_THROW(engine::stereo_eyes(centre, -0.1f), engine::Error);
    EXPECT_THROW(engine::stereo_eyes(centre, std::numeric_limits<float>::quiet_NaN()), engine::Error);
}

TEST(Image, SideBySidePutsTheLeftImageFirst) {
    const engine::Image left{2, 1, {1, 2, 3, 4, 5, 6, 7, 8}}, right{1, 1, {9, 10, 11, 12}};
    const engine::Image both = engine::side_by_side(left, right);
    EXPECT_EQ(both.width, 3);
    EXPECT_EQ(both.rgba, (std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
    EXPECT_THROW(engine::side_by_side(left, engine::Image{1, 2, std::vector<std::uint8_t>(8)}), engine::Error);
}

TEST(Camera, RejectsImpossibleSettings) {
    EXPECT_THROW(engine::make_look_at_camera({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 1.0f, 10, 10, 0.1f, 10.0f),
                 engine::Error);
    EXPECT_THROW(engine::make_look_at_camera({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 1.0f, 0, 10, 0.1f, 10.0f), engine::Error);
    EXPECT_THROW(engine::make_look_at_camera({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 1.0f, 10, 10, 1.0f, 0.5f), engine::Error);
    EXPECT_THROW(engine::make_look_at_camera({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 0.0f, 10, 10, 0.1f, 10.0f),
                 engine::Error);
}

TEST(Image, PngRoundTripAndComparison) {
    engine::Image a{3, 2, {}};
    for (int i = 0; i < 6; ++i) a.rgba.insert(a.rgba.end(), {std::uint8_t(i * 40), std::uint8_t(255 - i), 7, 255});
    const auto path = engine::test::output_dir("image") / "roundtrip.png";
    engine::write_png(path, a);
    const auto b = engine::read_png(path);
    EXPECT_EQ(b.width, 3);
    EXPECT_EQ(b.rgba, a.rgba);
    EXPECT_TRUE(std::isinf(engine::compare_images(a, b).psnr_db));

    auto c = a;
    c.pixel(1, 1)[0] = static_cast<std::uint8_t>(c.pixel(1, 1)[0] + 51);  // one channel off by 0.2
    const auto d = engine::compare_images(a, c);
    // MSE = 0.04 / 18 values -> PSNR = 10 log10(18 / 0.04) = 26.53 dB
    EXPECT_NEAR(d.psnr_db, 26.532, 0.01);
    EXPECT_EQ(d.max_channel_difference, 51);
    EXPECT_NEAR(d.fraction_over_threshold, 1.0 / 6.0, 1e-12);
    EXPECT_THROW(engine::compare_images(a, engine::Image{2, 2, std::vector<std::uint8_t>(16)}), engine::Error);
}

TEST(Image, CorruptPngIsAClearError) {
    const auto path = engine::test::output_dir("image") / "corrupt.png";
    engine::write_text_file_atomic(path, "\x89PNG not really");
    try {
        engine::read_png(path);
        FAIL();
    } catch (const engine::Error& e) {
        EXPECT_NE(std::string(e.what()).find("corrupt.png: cannot decode image"), std::string::npos) << e.what();
    }
}

// Depth for looking at: white at the nearest depth, dark grey at the farthest, by inverse depth
// between (in a 1–4 m range 2 m is a third of the way from 1/4 to 1), black where nothing is; a wrong
// size is an error.
TEST(Image, DepthImageGreysByInverseDepth) {
    const float inf = std::numeric_limits<float>::infinity();
    const engine::Image image = engine::depth_image({1.0f, 4.0f, 2.0f, inf}, 2, 2);
    EXPECT_EQ(image.pixel(0, 0)[0], 255);
    EXPECT_EQ(image.pixel(1, 0)[0], 48);
    EXPECT_EQ(image.pixel(0, 1)[0], 48 + 69);  // 48 + 207 · (1/2 − 1/4) / (1 − 1/4)
    EXPECT_EQ(image.pixel(1, 1)[0], 0);
    EXPECT_EQ(image.pixel(1, 1)[3], 255);
    EXPECT_THROW(engine::depth_image({1.0f, 2.0f}, 2, 2), engine::Error);
}

TEST(FileIo, AtomicWriteReplacesAndLeavesNoTemporaries) {
    const auto dir = engine::test::output_dir("file_io");
    const auto path = dir / "out.txt";
    engine::write_text_file_atomic(path, "first");
    engine::write_text_file_atomic(path, "second");
    EXPECT_EQ(engine::read_text_file(path), "second");
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
    // A write that cannot happen leaves the old file as it was.
    EXPECT_THROW(engine::write_text_file_atomic(dir / "out.txt" / "x", "y"), engine::Error);
    EXPECT_EQ(engine::read_text_file(path), "second");
}
