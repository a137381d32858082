// The temporal sweep without GL: the pair error and the pop on synthetic frames with closed-form answers
// (a pop, a fade over k frames, a pan), the
// supersampling factor, the dolly, orbit, walk, run and slow-dolly paths, path names and the checks
// of the options.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "splat_eval_report_test_helpers.h"
#include "splat_lod/eval/temporal_sweep.h"

namespace eval = splat_lod::eval;
using splat_eval_report_test::expect_error;

namespace {

// A 4×2 frame of one value, with pixel (0, 0) set to `corner` on every channel.
eval::FloatImage frame(float value, float corner) {
    eval::FloatImage image = eval::make_float_image(4, 2, value);
    for (int c = 0; c < 3; ++c) image.at(0, 0, c) = corner;
    return image;
}

TEST(TemporalError, AConstantOffsetFromTheReferenceCostsNothing) {
    const eval::FloatImage r0 = frame(0.2f, 0.5f), r1 = frame(0.4f, 0.1f);
    const eval::FloatImage m0 = frame(0.25f, 0.55f), m1 = frame(0.45f, 0.15f);  // reference + 0.05
    EXPECT_NEAR(eval::temporal_pair_error(m0, m1, r0, r1), 0.0, 1e-4);
    EXPECT_NEAR(eval::temporal_pair_error(r0, r1, r0, r1), 0.0, 1e-12) << "the reference against itself";
}

TEST(TemporalError, AStaticMethodAgainstAChangingReferenceCostsTheChangeIn8BitUnits) {
    const eval::FloatImage still = frame(0.3f, 0.3f);
    const eval::FloatImage r0 = frame(0.3f, 0.3f), r1 = frame(0.4f, 0.4f);  // every channel +0.1
    EXPECT_NEAR(eval::temporal_pair_error(still, still, r0, r1), 0.1 * 255.0, 1e-3);
    // The other way round: the method changes by 0.1 while the reference stays: the same error.
    EXPECT_NEAR(eval::temporal_pair_error(r0, r1, still, still), 0.1 * 255.0, 1e-3);
}

TEST(TemporalError, OppositeChangesInOnePixelAreAveragedOverPixelsAndChannels) {
    // One of 8 pixels: the method brightens by 0.2 where the reference darkens by 0.2, |0.2 + 0.2|;
    // the other pixels change alike (error 0).
    const eval::FloatImage m0 = frame(0.5f, 0.5f), m1 = frame(0.6f, 0.7f);
    const eval::FloatImage r0 = frame(0.5f, 0.5f), r1 = frame(0.6f, 0.3f);
    EXPECT_NEAR(eval::temporal_pair_error(m0, m1, r0, r1), 0.4 * 255.0 / 8.0, 1e-3);
    // Only one channel of that pixel: a third of it.
    eval::FloatImage m1_red = r1;
    m1_red.at(0, 0, 0) = 0.7f;
    EXPECT_NEAR(eval::temporal_pair_error(m0, m1_red, r0, r1), 0.4 * 255.0 / 24.0, 1e-3);
    const engine::Image picture = eval::temporal_difference_image(m0, m1, r0, r1, 2.0f);
    EXPECT_EQ(picture.pixel(0, 0)[0], 204) << "|0.4| x 2 = 0.8";
    EXPECT_EQ(picture.pixel(1, 0)[0], 0);
}

TEST(TemporalError, PairErrorsOfASequenceAndSizeChecks) {
    const std::vector<eval::FloatImage> reference{frame(0.1f, 0.1f), frame(0.2f, 0.2f), frame(0.2f, 0.2f)};
    const std::vector<eval::FloatImage> method{frame(0.1f, 0.1f), frame(0.1f, 0.1f), frame(0.3f, 0.3f)};
    const std::vector<double> errors = eval::temporal_pair_errors(method, reference);
    ASSERT_EQ(errors.size(), 2u);
    EXPECT_NEAR(errors[0], 0.1 * 255.0, 1e-3);  // the reference moved, the method did not
    EXPECT_NEAR(errors[1], 0.2 * 255.0, 1e-3);  // the method moved, the reference did not
    expect_error([&] { eval::temporal_pair_errors({frame(0, 0)}, reference); }, {"1 method frames against 3"});
    expect_error(
        [&] { eval::temporal_pair_error(frame(0, 0), eval::make_float_image(2, 2), frame(0, 0), frame(0, 0)); },
        {"sizes differ", "4x2 vs 2x2"});
}

// A 100 × 100 frame of `value` with the square [0, side)² set to `square` (every channel).
eval::FloatImage square_frame(float value, int side, float square) {
    eval::FloatImage image = eval::make_float_image(100, 100, value);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = square;
    return image;
}

TEST(TemporalPop, ASwitchInOneFrameCountsWholeWhereThePairErrorAveragesItAway) {
    // A 4 × 4 patch (0.16 % of the pixels) that the method switches by 0.4 while the reference stands still.
    const eval::FloatImage still = square_frame(0.3f, 4, 0.3f), popped = square_frame(0.3f, 4, 0.7f);
    EXPECT_NEAR(eval::temporal_pair_pop(still, popped, still, still), 0.4 * 255.0, 1e-3);
    EXPECT_NEAR(eval::temporal_pair_error(still, popped, still, still), 0.4 * 255.0 * 16.0 / 10000.0, 1e-3);
    // A patch of 9 pixels, under 0.1 % of the image, is below the percentile: no pop.
    EXPECT_NEAR(eval::temporal_pair_pop(still, square_frame(0.3f, 3, 0.7f), still, still), 0.0, 1e-9);
}

TEST(TemporalPop, TheSameSwitchFadedOverKFramesPopsOneKthPerPair) {
    const int k = 8;
    std::vector<eval::FloatImage> method, reference;
    for (int t = 0; t <= k; ++t) {
        method.push_back(square_frame(0.3f, 10, 0.3f + 0.4f * static_cast<float>(t) / k));
        reference.push_back(square_frame(0.3f, 10, 0.3f));
    }
    for (int t = 1; t <= k; ++t)
        EXPECT_NEAR(eval::temporal_pair_pop(method[t - 1], method[t], reference[t - 1], reference[t]), 0.4 * 255.0 / k,
                    1e-3)
            << "pair " << t;
}

TEST(TemporalPop, TheSwitchPopIsWhatTheSelectionChangeAloneDoesToTheFrame) {
    // Frame t drawn as it is and with frame t−1's selection: a patch switched in one frame counts
    // whole, faded over k frames 1/k, and a frame the selection does not change scores 0.
    const eval::FloatImage frozen = square_frame(0.3f, 4, 0.3f), popped = square_frame(0.3f, 4, 0.7f);
    EXPECT_NEAR(eval::selection_switch_pop(frozen, popped), 0.4 * 255.0, 1e-3);
    const int k = 8;
    EXPECT_NEAR(eval::selection_switch_pop(square_frame(0.3f, 10, 0.3f + 0.4f * 3 / k),
                                           square_frame(0.3f, 10, 0.3f + 0.4f * 4 / k)),
                0.4 * 255.0 / k, 1e-3);
    EXPECT_EQ(eval::selection_switch_pop(popped, popped), 0.0);
    expect_error([&] { eval::selection_switch_pop(popped, eval::make_float_image(2, 2)); }, {"sizes differ"});
}

TEST(TemporalPop, MotionTheReferenceHasTooCancels) {
    // A pan: the patch moves one pixel to the right per frame in both.
    std::vector<eval::FloatImage> frames;
    for (int t = 0; t < 4; ++t) {
        eval::FloatImage image = eval::make_float_image(100, 100, 0.2f);
        for (int y = 0; y < 20; ++y)
            for (int x = t; x < t + 20; ++x)
                for (int c = 0; c < 3; ++c) image.at(x, y, c) = 0.9f;
        frames.push_back(image);
    }
    for (int t = 1; t < 4; ++t)
        EXPECT_EQ(eval::temporal_pair_pop(frames[t - 1], frames[t], frames[t - 1], frames[t]), 0.0);
    expect_error([&] { eval::temporal_pair_pop(frames[0], eval::make_float_image(2, 2), frames[0], frames[0]); },
                 {"sizes differ"});
}

TEST(TemporalSweepSetup, SupersamplingIsTheLargestFactorUpTo4ThatFits) {
    EXPECT_EQ(eval::temporal_supersampling(64, 48, 2048), 4);
    EXPECT_EQ(eval::temporal_supersampling(512, 384, 2048), 4);
    EXPECT_EQ(eval::temporal_supersampling(600, 400, 2048), 3);
    EXPECT_EQ(eval::temporal_supersampling(1920, 1080, 2048), 1);
    EXPECT_EQ(eval::temporal_supersampling(256, 192, 600), 2);
    EXPECT_EQ(eval::temporal_supersampling(4000, 100, 2048), 0);
}

TEST(TemporalSweepSetup, DollyGoesOutTo64GeometricallyAndBack) {
    eval::CameraPose start;
    start.eye = {0, 0, 2};
    start.forward = {0, 0, -1};
    start.focus_distance = 2.0f;
    const auto poses = eval::dolly_path(start, 8);
    ASSERT_EQ(poses.size(), 8u);
    const double out_step = std::pow(64.0, 1.0 / 3.0), back_step = std::pow(64.0, 1.0 / 4.0);
    const double expected[] = {
        1, out_step, out_step * out_step, 64, 64 / back_step, 64 / std::pow(back_step, 2), 64 / std::pow(back_step, 3),
        1};
    for (std::size_t i = 0; i < poses.size(); ++i) {
        EXPECT_NEAR(poses[i].focus_distance / 2.0, expected[i], 1e-3 * expected[i]) << i;
        EXPECT_NEAR(glm::length(poses[i].target() - glm::vec3(0.0f)), 0.0f, 1e-3f) << "the target stays";
    }
    EXPECT_EQ(poses[3].name, "dolly 3 (64.00x)");
    EXPECT_EQ(eval::dolly_path(start, 5).size(), 5u);
    EXPECT_NEAR(eval::dolly_path(start, 5)[2].focus_distance, 128.0f, 1e-2f) << "odd: the middle frame is at 64x";
    expect_error([&] { eval::dolly_path(start, 3); }, {"--temporal-frames: 3 frames are too few"});
}

TEST(TemporalSweepSetup, WalkAndRunStepBackAtTheirSpeedUntilTheDistanceDoubles) {
    eval::CameraPose start;
    start.eye = {0, 0, 3};
    start.forward = {0, 0, -1};
    start.focus_distance = 3.0f;
    // 1.4 m/s at 60 fps in a scene of 1 m units: 1.4/60 units a frame, ⌈3 / (1.4/60)⌉ = 129 steps.
    const auto walk = eval::stride_path(start, eval::kWalkSpeed, 1.0, "walk");
    ASSERT_EQ(walk.size(), 130u);
    for (std::size_t i = 1; i < walk.size(); ++i) {
        EXPECT_NEAR(glm::length(walk[i].eye - walk[i - 1].eye), 1.4 / 60.0, 1e-5) << i;
        EXPECT_NEAR(glm::length(walk[i].target()), 0.0f, 1e-4f) << "the target stays";
    }
    EXPECT_GE(walk.back().focus_distance, 6.0f);
    EXPECT_LT(walk[128].focus_distance, 6.0f) << "the last frame is the first at or past 2x";
    EXPECT_EQ(walk[0].name, "walk 0 (1.000x)");
    // A scene in centimetres: the same speed is 100 times as many units, 3 steps.
    const auto run = eval::stride_path(start, eval::kRunSpeed, 0.01, "run");
    ASSERT_EQ(run.size(), 4u) << "at least kMinTemporalFrames frames";
    EXPECT_NEAR(glm::length(run[1].eye - run[0].eye), 5.0 / 60.0 / 0.01, 1e-3);
    // Units of a kilometre: capped at kMaxStrideFrames steps (6 s).
    EXPECT_EQ(eval::stride_path(start, eval::kWalkSpeed, 1e3, "walk").size(),
              static_cast<std::size_t>(eval::kMaxStrideFrames) + 1);
    expect_error([&] { eval::stride_path(start, eval::kWalkSpeed, 0.0, "walk"); }, {"must be > 0"});
}

TEST(TemporalSweepSetup, TheSlowDollyGoesFrom1To16AtAThirtySecondOfAnOctaveAFrame) {
    eval::CameraPose start;
    start.eye = {0, 0, 2};
    start.forward = {0, 0, -1};
    start.focus_distance = 2.0f;
    const auto poses = eval::slow_dolly_path(start);
    ASSERT_EQ(poses.size(), 129u);
    for (std::size_t i = 1; i < poses.size(); ++i)
        EXPECT_NEAR(poses[i].focus_distance / poses[i - 1].focus_distance, std::exp2(1.0 / 32.0), 1e-5) << i;
    EXPECT_NEAR(poses.back().focus_distance, 32.0f, 1e-3f);
    EXPECT_EQ(poses[32].name, "slow dolly 32 (2.000x)");
}

TEST(TemporalSweepSetup, PathsAreTheListedOnesInTheirOrder) {
    eval::TemporalOptions o;
    o.methods = eval::select_methods("full");
    eval::CameraPose start;
    start.eye = {0, 0, 2};
    start.focus_distance = 2.0f;
    const eval::SceneExtent extent{{0, 0, 0}, 1.0f};
    const auto all = eval::temporal_paths(o, start, extent, {0, 1, 0});
    ASSERT_EQ(all.size(), 5u);
    const char* names[] = {"dolly", "orbit", "walk", "run", "slow_dolly"};
    for (std::size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i].name, names[i]);
    EXPECT_EQ(all[2].poses.size(), 87u) << "2 units at 1.4/60 a frame: 86 steps";
    o.paths = "slow_dolly,walk";
    const auto two = eval::temporal_paths(o, start, extent, {0, 1, 0});
    ASSERT_EQ(two.size(), 2u);
    EXPECT_EQ(two[0].name, "slow_dolly");
    EXPECT_EQ(two[1].name, "walk");
}

TEST(TemporalSweepSetup, OrbitIsALevelCircleInEqualSteps) {
    const eval::SceneExtent extent{{1, 2, 3}, 2.0f};
    const auto poses = eval::orbit_path(extent, {0, 1, 0}, 24);
    ASSERT_EQ(poses.size(), 24u);
    const float distance = glm::length(poses[0].eye - extent.centre);
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const auto& pose = poses[i];
        EXPECT_NEAR(glm::length(pose.eye - extent.centre), distance, 1e-4f) << i;
        EXPECT_NEAR(pose.eye.y, poses[0].eye.y, 1e-4f) << "level, not alternating elevations";
        EXPECT_NEAR(glm::length(pose.target() - extent.centre), 0.0f, 1e-3f) << "looks at the centre";
        const auto& next = poses[(i + 1) % poses.size()];
        EXPECT_NEAR(glm::length(next.eye - pose.eye), glm::length(poses[1].eye - poses[0].eye), 1e-4f);
    }
}

TEST(TemporalSweepSetup, PathNamesAndOptionChecks) {
    EXPECT_EQ(eval::temporal_path_name("some/dir/walk path.json"), "walk_path");
    EXPECT_EQ(eval::temporal_path_name("cameras.json"), "cameras");
    EXPECT_EQ(eval::temporal_path_name("orbit.json"), "orbit_file");
    EXPECT_EQ(eval::temporal_path_name("walk.json"), "walk_file");
    EXPECT_EQ(eval::temporal_path_name("slow_dolly.json"), "slow_dolly_file");

    eval::TemporalOptions o;
    expect_error([&] { eval::validate_temporal_options(o); }, {"--methods: no method given"});
    o.methods = eval::select_methods("baseline,full");
    eval::validate_temporal_options(o);
    o.dolly_frames = 2;
    expect_error([&] { eval::validate_temporal_options(o); }, {"--temporal-frames: 2 frames are too few"});
    o.dolly_frames = 8;
    o.path_file = "/nonexistent/walk.json";
    expect_error([&] { eval::validate_temporal_options(o); }, {"--temporal-path /nonexistent/walk.json: no such file"});
    o.path_file.clear();
    o.paths = "walk,crawl";
    expect_error([&] { eval::validate_temporal_options(o); }, {"--temporal-paths: unknown path \"crawl\""});
    o.paths = "walk,run,walk";
    expect_error([&] { eval::validate_temporal_options(o); }, {"--temporal-paths: \"walk\" is listed twice"});
    o.paths = "walk";
    o.metres_per_unit = 0.0;
    expect_error([&] { eval::validate_temporal_options(o); }, {"--metres-per-unit: must be a finite number > 0"});
    o.metres_per_unit = std::nan("");
    expect_error([&] { eval::validate_temporal_options(o); }, {"--metres-per-unit"});
    o.metres_per_unit = 1.0;
    o.max_reference_side = 300;
    expect_error([&] { eval::validate_temporal_options(o); }, {"--max-reference-side: 300", "512\u00d7384"});
}

}  // namespace
