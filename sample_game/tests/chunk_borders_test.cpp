// The seam band of the profile's seam_ratio (chunk_borders.h) on a flat ground seen from above: each
// pixel's chunk is the one under it, the band is ±4 px around where the chunk borders project, the
// horizon is no border, and the ratio compares the error in the band with the error outside it.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"
#include "sample_game/harness/chunk_borders.h"

using namespace sample_game;

namespace {

// 3 × 3 chunks of 32 m, flat at height 2 (borders at x, z = ±16).
const ChunkGrid kGrid{96.0f, 32.0f, {}};

HeightGrid flat_ground() {
    return HeightGrid([](float, float) { return 2.0f; }, 96.0f, 64);
}

engine::CameraView from_above() {
    return engine::make_look_at_camera({3.0f, 52.0f, -2.0f}, {3.0f, 2.0f, -2.0f}, {0.0f, 0.0f, -1.0f},
                                       glm::radians(60.0f), 128, 96, 0.1f, 500.0f);
}

}  // namespace

// An import's chunk of span 1 covers 2 × 2 cells of a 4-cell grid: all four are one chunk (no border
// between them), the cells beside it their own.
TEST(ChunkBorders, AChunkOfSeveralCellsIsOneChunk) {
    splat_lod::world::WorldManifest m;
    m.size_m = 128.0f;
    m.chunk_size_m = 32.0f;
    splat_lod::world::ChunkEntry merged;
    merged.cell = {-2, -2};
    merged.span = 1;
    m.chunks.push_back(merged);
    const ChunkGrid grid = chunk_grid(m);
    const int corner = grid.chunk_at(-60.0f, -60.0f);
    EXPECT_EQ(corner, 0);
    EXPECT_EQ(grid.chunk_at(-10.0f, -60.0f), corner);
    EXPECT_EQ(grid.chunk_at(-60.0f, -10.0f), corner);
    EXPECT_EQ(grid.chunk_at(-10.0f, -10.0f), corner);
    EXPECT_EQ(grid.chunk_at(10.0f, -10.0f), 6);
    EXPECT_TRUE(chunk_grid(splat_lod::world::WorldManifest{}).owner.empty()) << "no spans: no owners";
}

TEST(ChunkBorders, EveryPixelShowsTheChunkUnderIt) {
    const engine::CameraView camera = from_above();
    const ChunkMap map = chunk_map(flat_ground(), kGrid, camera);
    ASSERT_EQ(map.chunk.size(), 128u * 96u);
    EXPECT_EQ(kGrid.count(), 3);
    EXPECT_EQ(kGrid.chunk_at(0.0f, 0.0f), 4);
    EXPECT_EQ(kGrid.chunk_at(-40.0f, -40.0f), 0);
    EXPECT_EQ(kGrid.chunk_at(40.0f, -40.0f), 2);
    EXPECT_EQ(kGrid.chunk_at(60.0f, 0.0f), -1);
    // The image centre looks at (3, 2, −2): the centre chunk.
    EXPECT_EQ(map.chunk[48 * 128 + 64], 4);
    const int before = map.chunk[48 * 128 + 2], after = map.chunk[48 * 128 + 125];
    EXPECT_NE(before, 4);
    EXPECT_NE(after, 4);
    EXPECT_NE(before, after);
}

TEST(ChunkBorders, TheBandLiesWhereTheBordersProject) {
    const engine::CameraView camera = from_above();
    const ChunkMap map = chunk_map(flat_ground(), kGrid, camera);
    const std::vector<std::uint8_t> band = border_band(map, 4);
    // Along the middle row, the borders x = −16 and x = +16 project to these columns.
    const float left = camera.project_to_pixel({-16.0f, 2.0f, -2.0f}).x;
    const float right = camera.project_to_pixel({16.0f, 2.0f, -2.0f}).x;
    ASSERT_GT(left, 8.0f);
    ASSERT_LT(right, 120.0f);
    const int row = 48;
    for (int x = 0; x < 128; ++x) {
        const float centre = static_cast<float>(x) + 0.5f;
        const float distance = std::min(std::abs(centre - left), std::abs(centre - right));
        const bool in_band = band[static_cast<std::size_t>(row * 128 + x)] != 0;
        SCOPED_TRACE("column " + std::to_string(x) + ", " + std::to_string(distance) + " px from a border");
        if (distance < 4.0f) {
            EXPECT_TRUE(in_band);
        }
        if (distance > 5.0f) {
            EXPECT_FALSE(in_band);
        }
    }
    // The borders z = ±16 run along rows: a column in the middle of the centre chunk is in the band
    // only near them.
    const float top = camera.project_to_pixel({3.0f, 2.0f, -16.0f}).y,
                bottom = camera.project_to_pixel({3.0f, 2.0f, 16.0f}).y;
    for (int y = 0; y < 96; ++y) {
        const float centre = static_cast<float>(y) + 0.5f;
        const float distance = std::min(std::abs(centre - top), std::abs(centre - bottom));
        const bool in_band = band[static_cast<std::size_t>(y * 128 + 64)] != 0;
        if (distance < 4.0f) {
            EXPECT_TRUE(in_band) << y;
        }
        if (distance > 5.0f) {
            EXPECT_FALSE(in_band) << y;
        }
    }
}

TEST(ChunkBorders, TheHorizonIsNoBorder) {
    // Level, 1.7 m above the middle of the centre chunk, looking along +x inside it: the upper half
    // is sky, and the band only where the border x = 16 crosses the ground.
    const auto camera = engine::make_look_at_camera({0.0f, 3.7f, 0.0f}, {10.0f, 3.7f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                                    glm::radians(60.0f), 96, 64, 0.1f, 500.0f);
    const ChunkMap map = chunk_map(flat_ground(), kGrid, camera);
    const std::vector<std::uint8_t> band = border_band(map, 4);
    for (int x = 0; x < 96; ++x) EXPECT_EQ(map.chunk[static_cast<std::size_t>(5 * 96 + x)], -1) << "sky above";
    EXPECT_EQ(map.chunk[static_cast<std::size_t>(63 * 96 + 48)], 4) << "the ground below";
    // Rows just above the horizon show sky, rows just below it the far chunk (x > 48 is outside the
    // world: sky again); no pixel of the sky is in the band.
    for (std::size_t i = 0; i < band.size(); ++i)
        if (map.chunk[i] < 0) {
            EXPECT_EQ(band[i], 0);
        }
    const float border_row = camera.project_to_pixel({16.0f, 2.0f, 0.0f}).y;
    EXPECT_TRUE(band[static_cast<std::size_t>(static_cast<int>(border_row) * 96 + 48)]);
    EXPECT_FALSE(band[static_cast<std::size_t>(63 * 96 + 48)]) << "near the camera, far from any border";
}

TEST(ChunkBorders, SeamRatioComparesTheBandWithTheRest) {
    const engine::CameraView camera = from_above();
    const ChunkMap map = chunk_map(flat_ground(), kGrid, camera);
    const std::vector<std::uint8_t> band = border_band(map, 4);
    auto reference = splat_lod::eval::make_float_image(128, 96, 0.5f);
    auto image = reference;
    for (std::size_t i = 0; i < band.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) image.rgb[3 * i + c] += band[i] ? 0.1f : 0.05f;
    const auto ratio = seam_ratio(image, reference, map, 4);
    ASSERT_TRUE(ratio.has_value());
    EXPECT_NEAR(*ratio, 2.0, 1e-4);
    EXPECT_FALSE(seam_ratio(reference, reference, map, 4).has_value()) << "no error outside the band";
    EXPECT_THROW(seam_ratio(splat_lod::eval::make_float_image(4, 4), reference, map, 4), engine::Error);
}

TEST(ChunkBorders, EveryPixelKnowsHowFarItsGroundIs) {
    const engine::CameraView camera = from_above();
    const ChunkMap map = chunk_map(flat_ground(), kGrid, camera);
    ASSERT_EQ(map.distance.size(), map.chunk.size());
    // Straight down from 50 m above the ground at the image centre; farther toward the corners.
    EXPECT_NEAR(map.distance[48 * 128 + 64], 50.0f, 0.05f);
    EXPECT_GT(map.distance[0], map.distance[48 * 128 + 64]);
    const auto level = engine::make_look_at_camera({0.0f, 3.7f, 0.0f}, {10.0f, 3.7f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                                   glm::radians(60.0f), 96, 64, 0.1f, 500.0f);
    const ChunkMap sky = chunk_map(flat_ground(), kGrid, level);
    EXPECT_EQ(sky.distance[static_cast<std::size_t>(5 * 96 + 48)], -1.0f) << "the sky has no ground";
}

// Error that grows with the distance alone (aliasing toward the horizon) makes seam_ratio large where
// the borders crowd far away; with the distance held fixed the ratio is 1. Error added along the
// borders raises both.
TEST(ChunkBorders, SeamRatioAtTheSameDistanceSeesOnlyTheBorders) {
    // Level, looking along +x from the −x edge of the world, slightly down: the chunk borders x = −16 and
    // x = 16 cross the ground at two distances, and the far one takes fewer rows.
    const auto camera = engine::make_look_at_camera({-46.0f, 4.0f, 0.0f}, {0.0f, 2.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                                    glm::radians(60.0f), 160, 120, 0.1f, 500.0f);
    const ChunkMap map = chunk_map(flat_ground(), kGrid, camera);
    const std::vector<std::uint8_t> band = border_band(map, 4);
    auto reference = splat_lod::eval::make_float_image(160, 120, 0.5f);
    auto by_distance = reference, with_seam = reference;
    std::size_t in_band = 0;
    for (std::size_t i = 0; i < band.size(); ++i) {
        if (map.chunk[i] < 0) continue;
        in_band += band[i];
        // Error a cubic of the distance: up to about 0.3 at the world's far edge.
        const float d = map.distance[i] / 96.0f, e = 0.3f * d * d * d;
        for (std::size_t c = 0; c < 3; ++c) {
            by_distance.rgb[3 * i + c] += e;
            with_seam.rgb[3 * i + c] += e + (band[i] ? 0.5f * e : 0.0f);
        }
    }
    ASSERT_GT(in_band, 100u);
    const auto plain = seam_ratio(by_distance, reference, map, 4);
    const auto same = seam_ratio_same_distance(by_distance, reference, map, 4);
    ASSERT_TRUE(plain.has_value() && same.has_value());
    EXPECT_NEAR(*same, 1.0, 0.1) << "no seam: the band's error is that of its distance";
    EXPECT_GT(std::abs(*plain - 1.0), 0.2) << "the plain ratio measures where the borders lie: " << *plain;
    const auto seam = seam_ratio_same_distance(with_seam, reference, map, 4);
    ASSERT_TRUE(seam.has_value());
    EXPECT_NEAR(*seam, 1.5, 0.15) << "half again the error along the borders";
    EXPECT_FALSE(seam_ratio_same_distance(reference, reference, map, 4).has_value()) << "no error at all";
    ChunkMap no_distances = map;
    no_distances.distance.clear();
    EXPECT_THROW(seam_ratio_same_distance(by_distance, reference, no_distances, 4), engine::Error);
}

// The seam picture: the error in grey (×8), the band tinted red, the sky dimmed blue.
TEST(ChunkBorders, SeamPictureShowsTheErrorAndTheBand) {
    const auto camera = engine::make_look_at_camera({0.0f, 3.7f, 0.0f}, {10.0f, 2.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                                    glm::radians(60.0f), 96, 64, 0.1f, 500.0f);
    const ChunkMap map = chunk_map(flat_ground(), kGrid, camera);
    const std::vector<std::uint8_t> band = border_band(map, 4);
    auto reference = splat_lod::eval::make_float_image(96, 64, 0.5f);
    auto image = reference;
    for (float& v : image.rgb) v += 10.0f / 255.0f;  // 10 levels everywhere: grey 80
    const engine::Image picture = seam_picture(image, reference, map, 4);
    ASSERT_EQ(picture.width, 96);
    ASSERT_EQ(picture.height, 64);
    int sky = 0, in_band = 0, plain = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 96; ++x) {
            const std::size_t i = static_cast<std::size_t>(y * 96 + x);
            const std::uint8_t* px = picture.pixel(x, y);
            if (map.chunk[i] < 0) {
                ++sky;
                EXPECT_EQ(px[0], 40);
                EXPECT_EQ(px[2], 104);
            } else if (band[i]) {
                ++in_band;
                EXPECT_EQ(px[0], 176);
                EXPECT_EQ(px[1], 80);
            } else {
                ++plain;
                EXPECT_EQ(px[0], 80);
                EXPECT_EQ(px[2], 80);
            }
            EXPECT_EQ(px[3], 255);
        }
    EXPECT_GT(sky, 0);
    EXPECT_GT(in_band, 0);
    EXPECT_GT(plain, 0);
    EXPECT_THROW(seam_picture(splat_lod::eval::make_float_image(4, 4), reference, map, 4), engine::Error);
}
