#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "test_support.h"

TEST(Camera, PixelConventionsAreTheDocumentedOnes) {
    const auto cam = engine::make_look_at_camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, glm::radians(90.0f), 200, 100, 0.1f, 100.0f);
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

TEST(Camera, RejectsImpossibleSettings) {
    EXPECT_THROW(engine::make_look_at_camera({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 1.0f, 10, 10, 0.1f, 10.0f), engine::Error);
    EXPECT_THROW(engine::make_look_at_camera({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 1.0f, 0, 10, 0.1f, 10.0f), engine::Error);
    EXPECT_THROW(engine::make_look_at_camera({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 1.0f, 10, 10, 1.0f, 0.5f), engine::Error);
    EXPECT_THROW(engine::make_look_at_camera({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 0.0f, 10, 10, 0.1f, 10.0f), engine::Error);
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
