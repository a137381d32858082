// The profile's records without GL: the CSV's columns and round trip, the summary's checks computed
// from the numbers (pass and fail), the streaming panel's history and failures, and the game
// settings handing the renderer's thresholds to the streamer.
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/core/message_bus.h"
#include "sample_game/game_settings.h"
#include "sample_game/harness/frame_record.h"
#include "sample_game/harness/profile_summary.h"
#include "sample_game/streaming_panel.h"
#include "test_support.h"

using namespace sample_game;

namespace {

// A path of 20 frames: 4 per segment, the overview (frames 12..15) 10 ms per frame with LOD.
std::vector<FrameRecord> lod_run(std::uint64_t resident_peak, std::uint64_t upload_peak) {
    std::vector<FrameRecord> records;
    for (int i = 0; i < 20; ++i) {
        FrameRecord r;
        r.frame = i;
        r.segment = static_cast<Segment>(i / 4);
        r.frame_ms = r.segment == Segment::overview ? 10.0 : 5.0 + i;
        r.resident_bytes = r.gpu_page_bytes = i == 13 ? resident_peak : resident_peak / 2;
        r.stream_upload_bytes = i == 3 ? upload_peak : upload_peak / 4;
        r.drawn_per_level = {100u + static_cast<unsigned>(i), 10, 5, 1};
        records.push_back(r);
    }
    return records;
}

std::vector<FrameRecord> baseline_run(double overview_ms) {
    std::vector<FrameRecord> records;
    for (int i : {0, 12, 13, 14, 15}) {
        FrameRecord r;
        r.run = "baseline";
        r.frame = i;
        r.segment = static_cast<Segment>(i / 4);
        r.frame_ms = r.segment == Segment::overview ? overview_ms : 50.0;
        records.push_back(r);
    }
    return records;
}

}  // namespace

TEST(ProfileRecords, CsvHasOneRowPerRecordUnderTheDocumentedColumns) {
    const auto folder = engine::test::output_dir("sample_game");
    const std::vector<FrameRecord> records = lod_run(100 * kMiB, 4 * kMiB);
    write_frames_csv(folder / "profile.csv", records, "test");
    const CsvTable table = read_csv(folder / "profile.csv");
    ASSERT_EQ(table.header.size(), frame_columns().size());
    for (std::size_t i = 0; i < frame_columns().size(); ++i) EXPECT_EQ(table.header[i], frame_columns()[i].name);
    ASSERT_EQ(table.rows.size(), records.size());
    EXPECT_EQ(table.rows[13][table.column("segment")], "overview");
    EXPECT_EQ(table.number(13, "resident_bytes"), static_cast<double>(100 * kMiB));
    EXPECT_EQ(table.number(5, "drawn_l1"), 105.0);
    EXPECT_EQ(table.rows[0][table.column("gpu_sort_ms")], "") << "a GPU span not measured stays empty";
    // Every column is explained in the file's comment header.
    const std::string text = engine::read_text_file(folder / "profile.csv");
    for (const auto& column : frame_columns())
        EXPECT_NE(text.find("#   " + column.name + ": "), std::string::npos) << column.name;
    EXPECT_THROW(table.column("no_such_column"), engine::Error);
}

TEST(ProfileSummary, PassesWhenTheMeasurementsAreWithinBudgetAndTheOverviewIsCheaper) {
    const ProfileSummary s = summarize(lod_run(100 * kMiB, 4 * kMiB), baseline_run(60.0), 128 * kMiB, 4 * kMiB);
    EXPECT_EQ(s.frames, 20);
    EXPECT_TRUE(s.memory.pass) << s.memory.text;
    EXPECT_TRUE(s.upload.pass) << s.upload.text;
    ASSERT_TRUE(s.overview_speedup.has_value());
    EXPECT_DOUBLE_EQ(*s.overview_speedup, 6.0);
    EXPECT_EQ(s.overview_pairs, 4);
    EXPECT_TRUE(s.overview.pass);
    EXPECT_EQ(s.peak_resident_bytes, 100 * kMiB);
    EXPECT_EQ(s.segments[static_cast<std::size_t>(Segment::overview)].frames, 4);
    EXPECT_DOUBLE_EQ(s.segments[static_cast<std::size_t>(Segment::overview)].median_ms, 10.0);
    EXPECT_EQ(s.segments[static_cast<std::size_t>(Segment::ground)].baseline_frames, 1);
    const std::string text = format_summary(s, {"a world", "settings", 12.0, "", {"out/profile.csv"}, ""});
    EXPECT_NE(text.find("PASS  memory"), std::string::npos) << text;
    EXPECT_NE(text.find("PASS  upload"), std::string::npos) << text;
    EXPECT_NE(text.find("PASS  overview"), std::string::npos) << text;
    EXPECT_NE(text.find("6.00x cheaper"), std::string::npos) << text;
}

// The splat pass's peak memory against the peak resident scene, whichever frames they fall on.
TEST(ProfileSummary, ThePassMemoryCheckComparesThePeaks) {
    std::vector<FrameRecord> records = lod_run(100 * kMiB, 4 * kMiB);
    ProfileSummary s = summarize(records, {}, 128 * kMiB, 4 * kMiB);
    EXPECT_FALSE(s.pass_memory.measured) << "no GPU totals recorded";
    for (auto& r : records) r.gpu_total_bytes = 60 * kMiB;
    records[3].gpu_total_bytes = 149 * kMiB;  // not the frame of the resident peak (13)
    records[7].selection_runs = 2;
    s = summarize(records, {}, 128 * kMiB, 4 * kMiB);
    EXPECT_TRUE(s.pass_memory.pass) << s.pass_memory.text;
    EXPECT_EQ(s.reselected_frames, 1);
    EXPECT_NE(s.pass_memory.text.find("1.49x"), std::string::npos) << s.pass_memory.text;
    records[3].gpu_total_bytes = 151 * kMiB;
    s = summarize(records, {}, 128 * kMiB, 4 * kMiB);
    EXPECT_FALSE(s.pass_memory.pass) << s.pass_memory.text;
}

TEST(ProfileSummary, FailsEachCheckFromTheNumbersAlone) {
    const ProfileSummary s = summarize(lod_run(200 * kMiB, 5 * kMiB), baseline_run(30.0), 128 * kMiB, 4 * kMiB);
    EXPECT_FALSE(s.memory.pass);
    EXPECT_EQ(s.frames_over_memory, 1);
    EXPECT_FALSE(s.upload.pass);
    EXPECT_EQ(s.frames_over_upload, 1);
    EXPECT_FALSE(s.overview.pass);
    EXPECT_DOUBLE_EQ(*s.overview_speedup, 3.0);
    const std::string text = format_summary(s, {});
    EXPECT_NE(text.find("FAIL  memory"), std::string::npos) << text;
    EXPECT_NE(text.find("FAIL  upload"), std::string::npos) << text;
    EXPECT_NE(text.find("FAIL  overview"), std::string::npos) << text;

    // GPU pages that disagree with the streamer's count fail the memory check too.
    std::vector<FrameRecord> lod = lod_run(100 * kMiB, 4 * kMiB);
    lod[7].gpu_page_bytes += 1;
    EXPECT_FALSE(summarize(lod, {}, 128 * kMiB, 4 * kMiB).memory.pass);
    // ... unless the difference is the props' splats (an import's far layer), which are not streamed.
    for (FrameRecord& r : lod) r.props_gpu_bytes = 1;
    for (std::size_t i = 0; i < lod.size(); ++i) lod[i].gpu_page_bytes = lod[i].resident_bytes + 1;
    EXPECT_TRUE(summarize(lod, {}, 128 * kMiB, 4 * kMiB).memory.pass);
    // Without baseline frames the overview is not measured: neither pass nor fail.
    const ProfileSummary no_baseline = summarize(lod_run(100 * kMiB, 4 * kMiB), {}, 128 * kMiB, 4 * kMiB);
    EXPECT_FALSE(no_baseline.overview.measured);
    EXPECT_NE(format_summary(no_baseline, {}).find("n/a   overview"), std::string::npos);
}

namespace {

// Reference frames 0 (ground) and 12, 13 (overview): LOD and baseline PSNR against the reference
// and the LOD image's seam ratio as given.
void set_reference(std::vector<FrameRecord>& lod, std::vector<FrameRecord>& baseline, double ground_loss_db,
                   double overview_gain_db, double overview_lod_db, double seam) {
    for (const int frame : {0, 12, 13}) {
        const bool overview = frame != 0;
        FrameRecord& l = lod[static_cast<std::size_t>(frame)];
        l.psnr_vs_reference = overview ? overview_lod_db : 35.0 - ground_loss_db;
        l.ssim_vs_reference = 0.9;
        l.seam_ratio = seam;
        for (FrameRecord& b : baseline)
            if (b.frame == frame) {
                b.psnr_vs_reference = overview ? overview_lod_db - overview_gain_db : 35.0;
                b.ssim_vs_reference = 0.8;
            }
    }
}

}  // namespace

TEST(ProfileSummary, ReferenceChecksComeFromTheNumbers) {
    std::vector<FrameRecord> lod = lod_run(100 * kMiB, 4 * kMiB), baseline = baseline_run(60.0);
    const ProfileSummary none = summarize(lod, baseline, 128 * kMiB, 4 * kMiB);
    EXPECT_TRUE(none.reference_frames.empty());
    EXPECT_FALSE(none.reference_loss.measured || none.reference_overview.measured || none.reference_seams.measured);
    EXPECT_NE(format_summary(none, {}).find("n/a   reference, seams"), std::string::npos);

    set_reference(lod, baseline, 0.4, 3.5, 31.0, 1.1);
    const ProfileSummary good = summarize(lod, baseline, 128 * kMiB, 4 * kMiB);
    ASSERT_EQ(good.reference_frames.size(), 3u);
    EXPECT_EQ(good.reference_frames[1].frame, 12);
    EXPECT_DOUBLE_EQ(good.reference_frames[1].baseline_psnr, 27.5);
    EXPECT_TRUE(good.reference_loss.pass) << good.reference_loss.text;
    EXPECT_TRUE(good.reference_overview.pass) << good.reference_overview.text;
    EXPECT_TRUE(good.reference_seams.pass) << good.reference_seams.text;
    const std::string text = format_summary(good, {"w", "s", 1.0, "", {}, "found, somewhere"});
    EXPECT_NE(text.find("reference: found, somewhere"), std::string::npos) << text;
    EXPECT_NE(text.find("against the reference"), std::string::npos) << text;
    EXPECT_NE(text.find("PASS  reference, overview"), std::string::npos) << text;

    set_reference(lod, baseline, 0.6, 2.5, 31.0, 1.3);  // too much worse, too little better, seams
    const ProfileSummary bad = summarize(lod, baseline, 128 * kMiB, 4 * kMiB);
    EXPECT_FALSE(bad.reference_loss.pass);
    EXPECT_FALSE(bad.reference_overview.pass);
    EXPECT_FALSE(bad.reference_seams.pass);
    set_reference(lod, baseline, 0.0, 5.0, 29.0, 1.0);  // better than the baseline, but under 30 dB
    EXPECT_FALSE(summarize(lod, baseline, 128 * kMiB, 4 * kMiB).reference_overview.pass);
}

TEST(StreamingPanel, KeepsTheLastFramesAndTheFailures) {
    engine::MessageBus bus;
    StreamingPanel panel(bus);
    for (int i = 0; i < 300; ++i) {
        StreamingSnapshot s;
        s.frame_ms = i;
        s.resident_bytes = static_cast<std::uint64_t>(i);
        panel.record(s);
    }
    ASSERT_EQ(panel.frame_ms().size(), StreamingPanel::kHistory);
    EXPECT_FLOAT_EQ(panel.frame_ms().front(), 60.0f);
    EXPECT_FLOAT_EQ(panel.frame_ms().back(), 299.0f);
    EXPECT_EQ(panel.latest().resident_bytes, 299u);
    bus.publish(plugin_msgs::StreamEvent{"chunk_+001_+000", plugin_msgs::StreamEventType::uploaded, 4, 1000, ""});
    for (int i = 0; i < 10; ++i)
        bus.publish(plugin_msgs::StreamEvent{"chunk_+00" + std::to_string(i) + "_+000",
                                             plugin_msgs::StreamEventType::failed, 0, 0,
                                             "chunks/x.lod.ply: truncated at byte " + std::to_string(i)});
    EXPECT_EQ(panel.failures_seen(), 10u);
    ASSERT_EQ(panel.failures().size(), StreamingPanel::kFailuresKept);
    EXPECT_EQ(panel.failures().back().chunk_id, "chunk_+009_+000");
    EXPECT_NE(panel.failures().back().message.find("byte 9"), std::string::npos);
}

TEST(GameSettings, TheStreamerUsesTheRenderersThresholds) {
    GameSettings s;
    s.lod.rule.size_threshold_px = 3.5f;
    s.lod.rule.rel_min = 0.7f;
    s.memory_budget_bytes = 64 * kMiB;
    s.upload_budget_bytes = 2 * kMiB;
    s.sync_streaming = true;
    const auto streamer = streamer_settings(s);
    EXPECT_EQ(streamer.rule.size_threshold_px, 3.5f);
    EXPECT_EQ(streamer.rule.rel_min, 0.7f);
    EXPECT_EQ(streamer.memory_budget_bytes, 64 * kMiB);
    EXPECT_EQ(streamer.upload_budget_bytes_per_frame, 2 * kMiB);
    EXPECT_FALSE(streamer.background_thread);
    EXPECT_EQ(streamer.gpu_sh_degree, 0);
    EXPECT_NO_THROW(validate(s));

    s.lod.rule.rel_min = 2.0f;  // above rel_max
    try {
        validate(s);
        FAIL() << "rel_min above rel_max was accepted";
    } catch (const engine::Error& e) {
        EXPECT_NE(std::string(e.what()).find("lod_settings.rel_min"), std::string::npos) << e.what();
    }
    s.lod.rule.rel_min = 0.5f;
    s.upload_budget_bytes = 100;  // below one GPU page
    EXPECT_THROW(validate(s), engine::Error);
}

namespace {

// The world-scale checks (7–11) from hand-made rows: each passes at its bar and fails just past it.
TEST(ProfileSummary, ScaleChecksFollowTheirBars) {
    std::vector<FrameRecord> lod = lod_run(10 * kMiB, 1 * kMiB);  // ground 5–8 ms, overview 10 ms
    const WorldScale scale{1000, 100 * kMiB, 500};
    for (auto& r : lod) {
        r.considered = 1000;
        r.culled = 550;
        r.skipped = 50;  // 60 % dropped before projection
        r.visible = r.segment == Segment::overview ? 1500 : 2500;
        if (r.segment == Segment::overview) r.resident_bytes = 15 * kMiB;
    }
    ProfileSummary s = summarize(lod, {}, 128 * kMiB, 4 * kMiB, scale);
    EXPECT_FALSE(s.scale_time.pass) << "the overview (10 ms) costs more than the ground (6.5 ms)";
    EXPECT_TRUE(s.scale_density.pass) << s.scale_density.text;
    EXPECT_TRUE(s.scale_culling.pass) << s.scale_culling.text;
    EXPECT_TRUE(s.scale_memory.pass) << s.scale_memory.text;
    EXPECT_FALSE(s.splat_budget.pass) << "2500 drawn against a budget of 500";

    for (auto& r : lod) {
        if (r.segment == Segment::overview) {
            r.frame_ms = 1.0;
            r.visible = 1501;
            r.resident_bytes = 16 * kMiB;
        } else {
            r.visible = 400;
        }
        if (r.segment == Segment::ground && r.frame == 2) r.culled = 540;
    }
    s = summarize(lod, {}, 128 * kMiB, 4 * kMiB, scale);
    EXPECT_TRUE(s.scale_time.pass) << s.scale_time.text;
    EXPECT_FALSE(s.scale_density.pass) << "1501 per 1000 pixels at the overview";
    EXPECT_FALSE(s.scale_culling.pass) << "one ground frame dropped only 59 %";
    EXPECT_FALSE(s.scale_memory.pass) << "16 % of the world resident";
    EXPECT_FALSE(s.splat_budget.pass) << "1501 drawn against 500";

    const ProfileSummary unmeasured = summarize(lod, {}, 128 * kMiB, 4 * kMiB);
    EXPECT_FALSE(unmeasured.scale_density.measured);
    EXPECT_FALSE(unmeasured.scale_memory.measured);
    EXPECT_FALSE(unmeasured.splat_budget.measured);
}

}  // namespace
