// Whether levels pop, without GL: the temporal error against the reference in closed form, the
// reference's frames coming in consecutive pairs, the frame strip keeping the window around the
// largest temporal error (or the fallback window) and writing it, and the summary's mean per run.
#include <algorithm>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "sample_game/game_settings.h"
#include "sample_game/harness/frame_strip.h"
#include "sample_game/harness/profile_summary.h"
#include "sample_game/harness/reference_cache.h"
#include "splat_lod/eval/sheet_drawing.h"
#include "test_support.h"

using namespace sample_game;
using splat_lod::eval::FloatImage;
using splat_lod::eval::make_float_image;

namespace {

// A path of `frames` poses, segments in the walkthrough's shares (ground 22 %, canopy 16 %, flyout
// 16 %, overview 26 %, return 20 %).
std::vector<PathPose> synthetic_path(std::size_t frames) {
    const double ends[kSegmentCount] = {0.22, 0.38, 0.54, 0.80, 1.0};
    std::vector<PathPose> poses(frames);
    for (std::size_t i = 0; i < frames; ++i) {
        const double t = (static_cast<double>(i) + 0.5) / static_cast<double>(frames);
        std::size_t k = 0;
        while (k + 1 < kSegmentCount && t >= ends[k]) ++k;
        poses[i].segment = static_cast<Segment>(k);
    }
    return poses;
}

// An 8-bit image of one grey level, its value the frame's index (to tell frames apart).
engine::Image grey(int width, int height, int value) {
    engine::Image image{width, height, std::vector<std::uint8_t>(std::size_t(width) * std::size_t(height) * 4, 255)};
    for (std::size_t p = 0; p < image.rgba.size(); p += 4)
        std::fill_n(image.rgba.begin() + static_cast<std::ptrdiff_t>(p), 3, static_cast<std::uint8_t>(value));
    return image;
}

std::vector<int> window_frames(const StripRecorder& strip) {
    std::vector<int> frames;
    for (const auto& f : strip.window()) frames.push_back(f.frame);
    return frames;
}

}  // namespace

TEST(TemporalError, IsTheMeanDifferenceOfTheRunsChangeFromTheReferencesIn8BitUnits) {
    // Closed form: the run brightens the left half by 10/255 between the frames, the reference
    // brightens every pixel by 4/255 and the right half of the run by 4/255 too. Left: |10 − 4| = 6,
    // right: 0; the mean over pixels and channels is 3.
    const int w = 8, h = 4;
    FloatImage previous = make_float_image(w, h, 0.5f), current = previous;
    FloatImage reference_previous = make_float_image(w, h, 0.25f), reference_current = reference_previous;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                current.at(x, y, c) += (x < w / 2 ? 10.0f : 4.0f) / 255.0f;
                reference_current.at(x, y, c) += 4.0f / 255.0f;
            }
    EXPECT_NEAR(temporal_error(previous, current, reference_previous, reference_current), 3.0, 1e-4);
    // The camera's own motion, the same in both, cancels; a run that does not change at all where the
    // reference does scores the reference's change.
    EXPECT_NEAR(temporal_error(reference_previous, reference_current, reference_previous, reference_current), 0.0,
                1e-9);
    EXPECT_NEAR(temporal_error(previous, previous, reference_previous, reference_current), 4.0, 1e-4);
    // One channel of one pixel off by 51/255 in the run's change: 51 / (8 · 4 · 3).
    FloatImage one_off = reference_current;
    one_off.at(2, 1, 0) += 0.2f;
    EXPECT_NEAR(temporal_error(reference_previous, one_off, reference_previous, reference_current), 51.0 / 96.0, 1e-4);
    EXPECT_THROW(temporal_error(previous, make_float_image(w, h + 1), reference_previous, reference_current),
                 engine::Error);
}

TEST(ReferenceFrames, ComeInConsecutivePairs) {
    const std::vector<PathPose> path = synthetic_path(100);
    const std::vector<std::size_t> frames = reference_frame_indices(path);
    ASSERT_EQ(frames.size(), 24u) << "12 chosen frames, each with its successor";
    for (std::size_t k = 0; k < frames.size(); k += 2) EXPECT_EQ(frames[k + 1], frames[k] + 1) << frames[k];
    EXPECT_TRUE(std::is_sorted(frames.begin(), frames.end()));
    std::set<Segment> segments;
    for (std::size_t k = 0; k < frames.size(); k += 2) segments.insert(path[frames[k]].segment);
    EXPECT_EQ(segments.size(), kSegmentCount);
    // On a short path chosen frames and successors overlap; every frame is still in a pair.
    const std::vector<PathPose> short_path = synthetic_path(20);
    const std::vector<std::size_t> few = reference_frame_indices(short_path);
    const std::set<std::size_t> chosen(few.begin(), few.end());
    EXPECT_EQ(chosen.size(), few.size()) << "no repeats";
    for (const std::size_t f : few) EXPECT_TRUE(chosen.count(f + 1) || (f > 0 && chosen.count(f - 1))) << f;
    EXPECT_LT(few.back(), 20u);
}

TEST(FrameStrip, KeepsTheFramesAroundTheLargestTemporalError) {
    StripRecorder strip(20, 12);
    for (int f = 0; f < 20; ++f) {
        const double error = f == 9 ? 5.0 : f == 14 ? 2.0 : f == 3 ? 1.0 : -1.0;
        strip.add(f, Segment::ground, grey(8, 4, f), error);
    }
    EXPECT_TRUE(strip.measured());
    EXPECT_EQ(window_frames(strip), (std::vector<int>{6, 7, 8, 9, 10, 11})) << "f-3 .. f+2 around the pair (8, 9)";
    EXPECT_EQ(strip.window()[3].image.rgba[0], 9);
    EXPECT_DOUBLE_EQ(strip.window()[3].temporal_error, 5.0);

    // Near the end of the path the window moves back onto it.
    StripRecorder late(20, 0);
    for (int f = 0; f < 20; ++f) late.add(f, Segment::ground, grey(8, 4, f), f == 19 ? 1.0 : -1.0);
    EXPECT_EQ(window_frames(late), (std::vector<int>{14, 15, 16, 17, 18, 19}));
    EXPECT_EQ(strip_start(1, 20), 0u);
    EXPECT_EQ(strip_start(9, 20), 6u);
    EXPECT_EQ(strip_start(9, 4), 0u);

    // Without any temporal error: the fallback window (clamped to the path).
    StripRecorder fallback(20, 16);
    for (int f = 0; f < 20; ++f) fallback.add(f, Segment::overview, grey(8, 4, f), -1.0);
    EXPECT_FALSE(fallback.measured());
    EXPECT_EQ(window_frames(fallback), (std::vector<int>{14, 15, 16, 17, 18, 19}));
}

TEST(FrameStrip, WritesTheReferenceRowWhereItExistsTheFramesAndTheTemporalErrorsPicture) {
    const auto folder = engine::test::output_dir("sample_game");
    const int w = 40, h = 20, thumbnail = 20;
    StripRecorder strip(10, 0);
    for (int f = 0; f < 10; ++f) strip.add(f, Segment::canopy, grey(w, h, 20 * f), f == 5 ? 3.0 : -1.0);
    std::map<int, FloatImage> reference;
    reference[4] = make_float_image(w, h, 0.5f);
    reference[5] = make_float_image(w, h, 0.6f);
    const auto path = folder / "frames_strip.png";
    std::filesystem::remove(path);
    ASSERT_TRUE(strip.write(path, reference, thumbnail));
    const engine::Image picture = engine::read_png(path);
    EXPECT_EQ(picture.width, 6 * (thumbnail + 2)) << "frames 2..7";
    const int row = h * thumbnail / w + splat_lod::eval::kLabelHeight + 2;  // thumbnail, label, gap
    ASSERT_EQ(picture.height, 3 * row) << "reference, frames, temporal error";
    // Frame 5 (fourth column) against 4: the run's change 20, the reference's 0.1 · 255 = 25.5; |20 − 25.5|
    // × 4 = 22. Frame 4 (third column) has no reference pair: black.
    const int y = 2 * row + splat_lod::eval::kLabelHeight + 5;
    EXPECT_EQ(picture.pixel(3 * (thumbnail + 2) + thumbnail / 2, y)[0], 22);
    EXPECT_EQ(picture.pixel(2 * (thumbnail + 2) + thumbnail / 2, y)[0], 0);
    // A reference without its predecessor: no error row; no reference at all: the frames alone.
    reference.erase(4);
    ASSERT_TRUE(strip.write(path, reference, thumbnail));
    EXPECT_EQ(engine::read_png(path).height, 2 * row);
    ASSERT_TRUE(strip.write(path, {}, thumbnail));
    EXPECT_EQ(engine::read_png(path).height, row);
    reference[4] = make_float_image(w + 1, h);
    reference[5] = make_float_image(w, h);
    EXPECT_THROW(strip.write(path, reference, thumbnail), engine::Error) << "a reference of another size";
    EXPECT_FALSE(StripRecorder(10, 0).write(folder / "empty_strip.png", {}, thumbnail)) << "nothing kept";
    EXPECT_FALSE(std::filesystem::exists(folder / "empty_strip.png"));
}

TEST(ProfileSummary, ReportsEachRunsMeanTemporalError) {
    std::vector<FrameRecord> lod(10), baseline;
    for (int f = 0; f < 10; ++f) lod[std::size_t(f)].frame = f;
    lod[5].temporal_error = 2.0;
    lod[8].temporal_error = 4.0;
    lod[5].pop = 40.0;  // a pop where the mean error is small
    lod[8].pop = 10.0;
    lod[5].psnr_vs_reference = lod[4].psnr_vs_reference = lod[8].psnr_vs_reference = 30.0;
    FrameRecord b;
    b.run = "baseline";
    b.frame = 5;
    b.temporal_error = 6.5;
    b.pop = 7.0;
    b.psnr_vs_reference = 28.0;
    baseline.push_back(b);
    const ProfileSummary s = summarize(lod, baseline, 128 * kMiB, 4 * kMiB);
    EXPECT_EQ(s.lod_temporal.pairs, 2);
    EXPECT_DOUBLE_EQ(s.lod_temporal.mean, 3.0);
    EXPECT_EQ(s.lod_temporal.largest_frame, 8);
    EXPECT_DOUBLE_EQ(s.lod_temporal.pop_peak, 40.0);
    EXPECT_EQ(s.lod_temporal.pop_peak_frame, 5) << "the pop's peak, not the mean error's";
    EXPECT_DOUBLE_EQ(s.lod_temporal.pop_mean, 25.0);
    EXPECT_EQ(s.baseline_temporal.pairs, 1);
    EXPECT_DOUBLE_EQ(s.baseline_temporal.mean, 6.5);
    ASSERT_EQ(s.reference_frames.size(), 3u);
    EXPECT_DOUBLE_EQ(s.reference_frames[1].lod_temporal_error, 2.0);
    EXPECT_DOUBLE_EQ(s.reference_frames[1].baseline_temporal_error, 6.5);
    EXPECT_DOUBLE_EQ(s.reference_frames[0].lod_temporal_error, -1.0);
    const std::string text = format_summary(s, {});
    EXPECT_NE(text.find("LOD 3.000 over 2 pairs"), std::string::npos) << text;
    EXPECT_NE(text.find("baseline 6.500 over 1 pairs"), std::string::npos) << text;
    EXPECT_NE(text.find("LOD peak 40.00 (frame 5), mean 25.00; baseline peak 7.00 (frame 5)"), std::string::npos)
        << text;
    EXPECT_EQ(temporal_errors({}).pairs, 0);
}
