// The evaluation's metrics, reference downsampling, camera readers and option checks (no GL).
#include <cmath>
#include <fstream>

#include "engine/core/error.h"
#include "splat_lod/core/camera_set.h"
#include "splat_lod/eval/eval_method.h"
#include "splat_lod/eval/eval_run.h"
#include "splat_lod/eval/image_metrics.h"
#include "splat_lod/splat_renderer.h"
#include "test_support.h"

namespace eval = splat_lod::eval;

namespace {

std::filesystem::path write_file(const std::string& name, const std::string& text) {
    const auto path = engine::test::output_dir("splat_eval_metrics") / name;
    std::ofstream(path) << text;
    return path;
}

// Expects engine::Error whose message contains every one of `parts`.
template <class F>
void expect_error(F&& f, std::initializer_list<std::string> parts) {
    try {
        f();
        ADD_FAILURE() << "no engine::Error thrown";
    } catch (const engine::Error& e) {
        for (const auto& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

TEST(SplatEvalMetrics, PsnrOfKnownNoiseMatchesClosedForm) {
    // Half the samples off by +0.1, half by −0.2: MSE = (0.01 + 0.04) / 2 = 0.025.
    const eval::FloatImage clean = eval::make_float_image(16, 8, 0.5f);
    eval::FloatImage noisy = clean;
    for (std::size_t i = 0; i < noisy.rgb.size(); ++i) noisy.rgb[i] += (i % 2 == 0) ? 0.1f : -0.2f;
    EXPECT_NEAR(eval::psnr(clean, noisy), -10.0 * std::log10(0.025), 1e-4);
    EXPECT_TRUE(std::isinf(eval::psnr(clean, clean)));
}

TEST(SplatEvalMetrics, PsnrRefusesDifferentSizes) {
    expect_error([] { eval::psnr(eval::make_float_image(4, 4), eval::make_float_image(4, 2)); },
                 {"psnr", "4x4", "4x2"});
}

eval::FloatImage ramp(int width, int height, float start, float step) {
    eval::FloatImage image = eval::make_float_image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c)
                image.at(x, y, c) = start + step * static_cast<float>(x) + 0.01f * static_cast<float>(c);
    return image;
}

TEST(SplatEvalMetrics, SsimOfIdenticalImagesIsOne) {
    const eval::FloatImage image = ramp(40, 30, 0.1f, 0.02f);
    EXPECT_NEAR(eval::ssim(image, image), 1.0, 1e-9);
}

TEST(SplatEvalMetrics, SsimOfShiftedRampMatchesClosedForm) {
    // One 11×11 window. A ramp shifted by one pixel is the ramp plus a constant: equal variances
    // and covariance = variance, so SSIM reduces to its luminance term, and the symmetric window's
    // mean of a ramp is its value at the centre column (x = 5).
    const float step = 0.02f;
    const eval::FloatImage a = ramp(11, 11, 0.3f, step), b = ramp(11, 11, 0.3f + step, step);
    double expected = 0.0;
    for (int c = 0; c < 3; ++c) {
        const double mu_a = 0.3 + step * 5 + 0.01 * c, mu_b = mu_a + step, c1 = 1e-4;
        expected += (2 * mu_a * mu_b + c1) / (mu_a * mu_a + mu_b * mu_b + c1) / 3.0;
    }
    const double value = eval::ssim(a, b);
    EXPECT_LT(value, 1.0);
    EXPECT_NEAR(value, expected, 1e-5);
}

TEST(SplatEvalMetrics, SsimOfShiftedTextureIsWellBelowOne) {
    eval::FloatImage a = eval::make_float_image(32, 32), b = a;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c) {
                a.at(x, y, c) = ((x / 2 + y / 2) % 2) ? 0.8f : 0.2f;
                b.at(x, y, c) = (((x + 1) / 2 + y / 2) % 2) ? 0.8f : 0.2f;
            }
    EXPECT_LT(eval::ssim(a, b), 0.5);
}

TEST(SplatEvalMetrics, AreaAverageOfKnownImage) {
    eval::FloatImage image = eval::make_float_image(4, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) image.at(x, y, 0) = static_cast<float>(x + 4 * y);  // 0..7
    const eval::FloatImage half = eval::area_average(image, 2);
    ASSERT_EQ(half.width, 2);
    ASSERT_EQ(half.height, 1);
    EXPECT_FLOAT_EQ(half.at(0, 0, 0), (0 + 1 + 4 + 5) / 4.0f);
    EXPECT_FLOAT_EQ(half.at(1, 0, 0), (2 + 3 + 6 + 7) / 4.0f);
    EXPECT_FLOAT_EQ(half.at(1, 0, 1), 0.0f);
    const eval::FloatImage same = eval::area_average(image, 1);
    EXPECT_EQ(same.rgb, image.rgb);
}

TEST(SplatEvalMetrics, ImpossibleScalesAreRefused) {
    const auto image = eval::make_float_image(8, 4);
    expect_error([&] { eval::area_average(image, 0); }, {"scale 0", "not a positive integer"});
    expect_error([&] { eval::area_average(image, 3); }, {"scale 3", "does not divide", "8x4"});
    expect_error([&] { eval::area_average(image, 8); }, {"scale 8", "larger than the image"});
    expect_error([] { eval::parse_int_list("1,0", "--scales"); }, {"--scales", "\"0\""});
    expect_error([] { eval::parse_int_list("-2", "--scales"); }, {"--scales", "\"-2\""});
    expect_error([] { eval::parse_int_list("2x", "--scales"); }, {"--scales", "\"2x\""});
    eval::EvalOptions options;
    options.methods = eval::select_methods("baseline");
    options.width = 96;
    options.height = 64;
    options.scales = {1, 2, 3};
    expect_error([&] { eval::validate_options(options); }, {"--scales", "scale 3", "96x64"});
    options.scales = {128};
    expect_error([&] { eval::validate_options(options); }, {"--scales", "larger"});
}

TEST(SplatEvalMetrics, UnknownMethodIsRefused) {
    expect_error([] { eval::select_methods("baseline,fancy"); }, {"fancy", "baseline_mip"});
    EXPECT_EQ(eval::select_methods("baseline_mip,baseline").front().name, "baseline_mip");
}

TEST(SplatEvalMetrics, FullWithABandIsAMethod) {
    const auto methods = eval::select_methods("full,full_hard,full@0.5,full@1:inside,full@0.25:auto");
    ASSERT_EQ(methods.size(), 5u);
    std::vector<double> bands, overlap_bands;
    std::vector<plugin_msgs::TransitionPlacement> placements;
    for (const auto& method : methods) {
        splat_lod::SplatPassSettings settings;
        plugin_msgs::LodSettings lod;
        method.configure(lod, settings);
        // Every level and the coverage rule; the band that takes effect (0 without transitions).
        const auto traits = plugin_msgs::traits(lod.rule.mode);
        EXPECT_TRUE(traits.all_levels && traits.coverage_rule);
        bands.push_back(traits.transitions ? lod.rule.transition_band : 0.0);
        overlap_bands.push_back(traits.transitions ? lod.rule.overlap_transition_band : 0.0);
        placements.push_back(lod.rule.transition_placement);
    }
    EXPECT_EQ(bands, (std::vector<double>{plugin_msgs::LodRule::kDefaultTransitionBand, 0.0, 0.5, 1.0, 0.25}));
    EXPECT_EQ(overlap_bands,
              (std::vector<double>{plugin_msgs::LodRule::kDefaultOverlapTransitionBand, 0.0, 0.5, 1.0, 0.25}));
    using plugin_msgs::TransitionPlacement;
    EXPECT_EQ(placements,
              (std::vector<TransitionPlacement>{TransitionPlacement::automatic, TransitionPlacement::automatic,
                                                TransitionPlacement::before, TransitionPlacement::inside,
                                                TransitionPlacement::automatic}));
    expect_error([] { eval::select_methods("full@-1"); }, {"full@-1", "[0, 4] octaves"});
    expect_error([] { eval::select_methods("full@wide"); }, {"full@wide"});
    expect_error([] { eval::select_methods("full@0.5:after"); },
                 {"full@0.5:after", "inside, before, centred, staggered, auto"});
    expect_error([] { eval::select_methods("full@0.5:"); }, {"full@0.5:"});
    expect_error([] { eval::select_methods("full@0.5,full@0.5"); }, {"listed twice"});
}

const char* kInriaCamera = R"([{"id": 0, "img_name": "frame0", "width": 640, "height": 480,
  "position": [0, 0, 0], "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fx": 514.7, "fy": 514.7}])";

TEST(SplatEvalCameras, InriaCamerasConvertOpenCvAxes) {
    const auto poses = eval::read_inria_cameras(write_file("inria.json", kInriaCamera));
    ASSERT_EQ(poses.size(), 1u);
    EXPECT_EQ(poses[0].name, "frame0");
    EXPECT_NEAR(glm::degrees(poses[0].fov_y), 2.0 * glm::degrees(std::atan(240.0 / 514.7)), 1e-3);
    const auto view = eval::make_view(poses[0], 640, 480);
    // OpenCV: +z is forward and +y points down the image.
    const glm::vec3 ahead = view.project_to_pixel({0, 0, 5});
    EXPECT_NEAR(ahead.x, 320.0f, 1e-3f);
    EXPECT_NEAR(ahead.y, 240.0f, 1e-3f);
    EXPECT_GT(view.project_to_pixel({0, 1, 5}).y, 240.0f);
    EXPECT_GT(view.project_to_pixel({1, 0, 5}).x, 320.0f);
}

TEST(SplatEvalCameras, CorruptInriaFilesNameFileAndProblem) {
    expect_error([] { eval::read_inria_cameras(write_file("broken.json", "[{\"id\": 0,")); },
                 {"broken.json", "not valid JSON"});
    expect_error([] { eval::read_inria_cameras(write_file("empty.json", "[]")); }, {"empty.json", "empty"});
    expect_error([] { eval::read_inria_cameras(write_file("object.json", "{}")); }, {"object.json", "array"});
    std::string no_fy = kInriaCamera;
    no_fy.replace(no_fy.find("\"fy\""), 4, "\"fz\"");
    expect_error([&] { eval::read_inria_cameras(write_file("no_fy.json", no_fy)); },
                 {"no_fy.json", "camera 0", "\"fy\""});
    std::string bad_rotation = kInriaCamera;
    bad_rotation.replace(bad_rotation.find("[0, 0, 1]]"), 10, "[0, 0, 1, 4]]");
    expect_error([&] { eval::read_inria_cameras(write_file("rot.json", bad_rotation)); }, {"rot.json", "\"rotation\""});
    expect_error([] { eval::read_inria_cameras(write_file("missing.json", "[")); }, {"missing.json"});
    expect_error([] { eval::read_inria_cameras("/nonexistent/cameras.json"); }, {"/nonexistent/cameras.json"});
}

TEST(SplatEvalCameras, CameraPathFile) {
    const auto poses = eval::read_camera_path(
        write_file("path.json", R"([{"eye": [0, 0, 5], "target": [0, 0, 0], "fov_y_deg": 40, "name": "front"}])"));
    ASSERT_EQ(poses.size(), 1u);
    EXPECT_EQ(poses[0].name, "front");
    EXPECT_NEAR(poses[0].focus_distance, 5.0f, 1e-6f);
    const auto far = eval::dolly(poses[0], 4.0f);
    EXPECT_NEAR(far.eye.z, 20.0f, 1e-5f);
    EXPECT_NEAR(glm::length(far.target()), 0.0f, 1e-5f);
    expect_error([] { eval::read_camera_path(write_file("p1.json", R"([{"eye": [0, 0, 5]}])")); },
                 {"p1.json", "camera 0", "missing \"target\""});
    expect_error([] { eval::read_camera_path(write_file("p2.json", R"([{"eye": [1, 1, 1], "target": [1, 1, 1]}])")); },
                 {"p2.json", "coincide"});
    expect_error(
        [] { eval::read_camera_path(write_file("p3.json", R"([{"eye": [0, "a", 5], "target": [0, 0, 0]}])")); },
        {"p3.json", "\"eye\""});
    expect_error([] { eval::load_camera_set("orbit:zero", {}, {0, 1, 0}); }, {"orbit:zero"});
}

}  // namespace
