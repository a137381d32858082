// The frame's work savings against the plain forms they replace (docs/algorithms.md §1): the exact
// tile footprint (the same bytes as every tile of the bounding box, fewer pairs), one-word sort keys
// (the same image within the depth quantisation) and the raster's two ways of reading splats (the
// same bytes).
#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/render/camera.h"
#include "gpu_fixture.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/splat_renderer.h"
#include "splat_test_data.h"
#include "splat_test_scenes.h"
#include "test_support.h"

using engine::test::GaussianSpec;

namespace {

using Clouds = std::vector<std::shared_ptr<const splat_lod::SplatCloud>>;

class SplatRasterTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness harness;
    splat_lod::SplatRenderer pass{harness.engine().renderer()};

    struct Frame {
        engine::Image image;
        std::uint64_t pairs = 0;
    };
    Frame render(const Clouds& clouds, const engine::CameraView& camera) {
        Frame f{harness.render(clouds, camera)};
        pass.wait_for_statistics(harness.engine().bus());
        EXPECT_FALSE(pass.latest_statistics()->overflowed);
        f.pairs = pass.latest_statistics()->tile_splat_pairs;
        return f;
    }
    // The frame with the bounding-box footprint and with the exact one: the same bytes, no more pairs.
    // Returns the pairs (bounding box, exact).
    std::pair<std::uint64_t, std::uint64_t> expect_same_bytes_with_exact_tiles(const Clouds& clouds,
                                                                               const engine::CameraView& camera) {
        pass.settings().exact_tiles = false;
        const Frame box = render(clouds, camera);
        pass.settings().exact_tiles = true;
        const Frame exact = render(clouds, camera);
        EXPECT_EQ(box.image.rgba, exact.image.rgba) << "the exact footprint must not change a pixel";
        EXPECT_LE(exact.pairs, box.pairs);
        return {box.pairs, exact.pairs};
    }
};

std::shared_ptr<const splat_lod::SplatCloud> shared(splat_lod::SplatCloud cloud) {
    return std::make_shared<const splat_lod::SplatCloud>(std::move(cloud));
}

// The hard cases of a footprint: needles at many angles (anisotropy up to 1000:1) crossing tile
// corners, discs from a tenth of a pixel to larger than the image, opacities from just above 1/255 to
// 1, splats half off every edge, and a random crowd.
Clouds footprint_cases() {
    std::vector<GaussianSpec> specs;
    for (int a = 0; a < 24; ++a) {
        const float angle = 3.14159265f * float(a) / 24.0f;
        const glm::vec4 q(std::cos(angle / 2), 0.0f, 0.0f, std::sin(angle / 2));  // about the view axis
        const float x = -0.9f + 0.075f * float(a);
        specs.push_back({{x, 0.35f, 0.0f}, {-1.2f, -8.0f, -8.0f}, q, 3.0f, {1.0f, 0.4f, 0.1f}});
        specs.push_back({{x, -0.35f, 0.0f}, {-2.0f, -4.5f, -6.0f}, q, -5.5f + 0.4f * float(a), {0.2f, 0.8f, 0.3f}});
    }
    const float log_scales[] = {-9.0f, -6.0f, -4.0f, -2.5f, -1.0f, 1.5f};
    for (int k = 0; k < 6; ++k)
        specs.push_back(
            {{-0.5f + 0.2f * float(k), 0.0f, -0.2f}, glm::vec3(log_scales[k]), {1, 0, 0, 0}, 1.0f, glm::vec3(0.5f)});
    const glm::vec3 edges[] = {{1.3f, 0.0f, 0.0f},  {-1.3f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                               {0.0f, -1.0f, 0.0f}, {1.3f, 1.0f, 0.0f},  {-1.3f, -1.0f, 0.0f}};
    for (const auto& e : edges)
        specs.push_back({e, {-1.5f, -3.0f, -6.0f}, {0.9f, 0.1f, 0.2f, 0.4f}, 2.0f, glm::vec3(0.9f)});
    std::mt19937 rng(19);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 3000; ++i)
        specs.push_back({{1.2f * u(rng), 0.9f * u(rng), 0.5f * u(rng)},
                         {-4.0f + 1.5f * u(rng), -4.0f + 1.5f * u(rng), -4.0f + 1.5f * u(rng)},
                         {u(rng), u(rng), u(rng), u(rng)},
                         3.0f * u(rng),
                         {0.5f + 0.5f * u(rng), 0.5f, 0.5f - 0.5f * u(rng)}});
    return {shared(engine::test::make_cloud(specs))};
}

engine::CameraView footprint_camera(int width, int height) {
    return engine::make_look_at_camera({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), width, height, 0.1f,
                                       100.0f);
}

}  // namespace

TEST_F(SplatRasterTest, ExactFootprintDrawsTheSameBytesWithFewerPairsOnHardCases) {
    const Clouds clouds = footprint_cases();
    for (const std::uint32_t tile : {4u, 8u, 16u}) {
        SCOPED_TRACE("tile " + std::to_string(tile));
        pass.settings().tile_size = tile;
        const auto [box, exact] = expect_same_bytes_with_exact_tiles(clouds, footprint_camera(333, 251));
        EXPECT_LT(double(exact), 0.9 * double(box)) << "needles across tile corners leave many box tiles untouched";
    }
    // Below render scale 1 the raster also writes derivatives: the footprint must not change them either.
    pass.settings().tile_size = 16;
    harness.edit_lod([](plugin_msgs::LodSettings& lod) { lod.render_scale = 0.5f; });
    expect_same_bytes_with_exact_tiles(clouds, footprint_camera(333, 251));
    const auto low_exact = pass.read_low_res_image();
    pass.settings().exact_tiles = false;
    render(clouds, footprint_camera(333, 251));
    const auto low_box = pass.read_low_res_image();
    EXPECT_EQ(low_exact.value, low_box.value);
    EXPECT_EQ(low_exact.dxy, low_box.dxy);
}

TEST_F(SplatRasterTest, ExactFootprintDrawsTheSameBytesOnRealCaptures) {
    for (const auto& scene : engine::test::real_splat_scenes()) {
        if (!std::filesystem::exists(scene.path)) continue;
        SCOPED_TRACE(scene.name);
        const Clouds clouds{shared(splat_lod::load_splat_file(scene.path))};
        const auto cameras = engine::test::orbit_cameras(*clouds[0], scene.up, 2, 320, 180);
        for (const auto& camera : cameras) {
            const auto [box, exact] = expect_same_bytes_with_exact_tiles(clouds, camera);
            const double ratio = double(box) / double(std::max<std::uint64_t>(exact, 1));
            RecordProperty(scene.name + "_pair_ratio", std::to_string(ratio));
        }
    }
}

// With texel fetches the project and bin passes also read their inputs through buffer textures; with
// shared-memory batches every pass reads storage buffers. Two instances (the second moved, turned and
// scaled, with SH degree 3) so that the instance records and every SH coefficient are read both ways.
TEST_F(SplatRasterTest, TexelAndSharedFetchDrawTheSameBytes) {
    Clouds clouds = footprint_cases();
    splat_lod::SplatCloud with_sh = *clouds[0];
    with_sh.set_sh_degree(3);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-0.4f, 0.4f);
    for (float& c : with_sh.sh_rest) c = u(rng);
    clouds.push_back(shared(std::move(with_sh)));
    const glm::mat4 second = glm::scale(
        glm::rotate(glm::translate(glm::mat4(1.0f), {0.3f, -0.2f, -0.5f}), 0.6f, glm::normalize(glm::vec3(1, 2, 0.5f))),
        glm::vec3(0.7f));
    const std::vector<glm::mat4> models{glm::mat4(1.0f), second};
    const auto render_both = [&](const engine::CameraView& camera) {
        Frame f{harness.render(clouds, camera, glm::vec3(0.0f), models)};
        pass.wait_for_statistics(harness.engine().bus());
        f.pairs = pass.latest_statistics()->tile_splat_pairs;
        return f;
    };
    // Both storages: the compact records and SH bytes decode the same through texels and buffers.
    for (const auto storage : {splat_lod::GpuStorage::compact, splat_lod::GpuStorage::full})
        for (const float scale : {1.0f, 0.5f}) {
            SCOPED_TRACE("render scale " + std::to_string(scale) +
                         (storage == splat_lod::GpuStorage::compact ? ", compact" : ", full"));
            pass.settings().gpu_storage = storage;
            harness.edit_lod([&](plugin_msgs::LodSettings& lod) { lod.render_scale = scale; });
            pass.settings().raster_fetch = splat_lod::RasterFetch::texel;
            const Frame texel = render_both(footprint_camera(200, 120));
            EXPECT_EQ(pass.raster_fetch_in_use(), splat_lod::RasterFetch::texel);
            pass.settings().raster_fetch = splat_lod::RasterFetch::shared;
            const Frame staged = render_both(footprint_camera(200, 120));
            EXPECT_EQ(pass.raster_fetch_in_use(), splat_lod::RasterFetch::shared);
            EXPECT_EQ(texel.image.rgba, staged.image.rgba);
            EXPECT_EQ(texel.pairs, staged.pairs);
            EXPECT_GT(texel.pairs, 0u);
        }
    // Automatic: texel fetches on a CPU driver, shared-memory batches on a GPU.
    pass.settings().raster_fetch = splat_lod::RasterFetch::automatic;
    render(clouds, footprint_camera(64, 48));
    const bool cpu_driver = engine::test::gl_context().info().renderer.find("llvmpipe") != std::string::npos;
    EXPECT_EQ(pass.raster_fetch_in_use(), cpu_driver ? splat_lod::RasterFetch::texel : splat_lod::RasterFetch::shared);
}

// One-word keys quantise the depth to the frame's range: order can change only between splats whose
// depths differ by less than 2^(shift − 23) of the depth. A frame spanning depths 0.3 … 3000 (the
// widest step) and coincident splats of different colours: the image stays within 60 dB of the
// two-word keys' and the same frame twice gives the same bytes.
TEST_F(SplatRasterTest, OneWordSortKeysKeepTheImageAcrossAWideDepthRange) {
    std::vector<GaussianSpec> specs;
    for (int i = 0; i < 400; ++i) {
        const float depth = 0.3f * std::pow(10000.0f, float(i) / 399.0f);
        const float spread = 0.4f * depth;
        specs.push_back({{spread * std::sin(float(i)), spread * std::cos(1.3f * float(i)), 3.0f - depth},
                         glm::vec3(std::log(0.05f * depth)),
                         {1, 0, 0, 0},
                         1.5f,
                         {float(i % 3) / 2.0f, float(i % 5) / 4.0f, 0.5f}});
    }
    for (int i = 0; i < 50; ++i)  // coincident: the stable sort keeps their index order either way
        specs.push_back({{0.1f, 0.1f, 2.0f}, glm::vec3(-3.0f), {1, 0, 0, 0}, 0.5f, {float(i) / 49.0f, 0.3f, 0.6f}});
    const Clouds clouds{shared(engine::test::make_cloud(specs))};
    const auto camera =
        engine::make_look_at_camera({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), 320, 240, 0.1f, 1e5f);
    pass.settings().compact_sort_keys = false;
    const Frame wide = render(clouds, camera);
    pass.settings().compact_sort_keys = true;
    const Frame compact = render(clouds, camera);
    EXPECT_EQ(compact.pairs, wide.pairs);
    EXPECT_GE(engine::compare_images(compact.image, wide.image).psnr_db, 60.0);
    EXPECT_EQ(render(clouds, camera).image.rgba, compact.image.rgba);
    // 1024² at 4-px tiles: 65,536 tiles (17 bits) leave the depth under 16 bits: the keys stay two words.
    pass.settings().tile_size = 4;
    const auto big =
        engine::make_look_at_camera({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), 1024, 1024, 0.1f, 1e5f);
    pass.settings().compact_sort_keys = false;
    const Frame big_wide = render(clouds, big);
    pass.settings().compact_sort_keys = true;
    EXPECT_EQ(render(clouds, big).image.rgba, big_wide.image.rgba);
}
