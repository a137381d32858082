// The chunk streamer (splat_lod/stream/chunk_streamer.h) loading and unloading the levels of the
// small synthetic world of chunk_streamer_test_helpers.h: the stream policy's arithmetic, levels that
// load at their distance coarse first and unload beyond the hysteresis, the per-frame upload and the
// memory budgets, paged accounting, settings checks, release_all and the events and residency reports
// on the bus. Failed and background reads: chunk_streamer_test_reads.cpp; chunk groups:
// chunk_streamer_test_groups.cpp.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "chunk_streamer_test_helpers.h"
#include "engine/core/error.h"
#include "engine/core/message_bus.h"
#include "splat_lod/msgs/lod_settings.h"
#include "splat_lod/msgs/stream_events.h"
#include "splat_lod/stream/chunk_streamer.h"

namespace sw = splat_lod::world;
using namespace chunk_streamer_test;
using plugin_msgs::ResidencyReport;
using plugin_msgs::StreamEvent;
using plugin_msgs::StreamEventType;

TEST(StreamPolicy, GpuBytesDistancesAndLoadDistances) {
    // Compact slots: the 20-byte record and the higher SH bands, 4 words at degree 3.
    EXPECT_EQ(sw::gpu_bytes(1, 3), 20u + 16u);
    EXPECT_EQ(sw::gpu_bytes(10, 0), 200u);
    EXPECT_EQ(sw::gpu_bytes(1, 3, kFullSlots), 256u);
    EXPECT_EQ(sw::gpu_bytes(10, 0, kFullSlots), 760u);
    // As the incremental GPU scene stores uploads: whole pages of 256 slots plus a 48-byte cluster
    // record, and when compact an 80-byte page codec.
    const sw::PageLayout pages;
    EXPECT_EQ(sw::gpu_bytes(0, 0, pages), 0u);
    EXPECT_EQ(sw::gpu_bytes(1, 0, pages), 256u * 20u + 128u);
    EXPECT_EQ(sw::gpu_bytes(300, 0, pages), 2u * (256u * 20u + 128u));
    EXPECT_EQ(sw::max_gaussians_within(3u * (256u * 20u + 128u) - 1u, 0, pages), 512u);
    EXPECT_EQ(sw::max_gaussians_within(100u, 0, pages), 0u);
    const sw::PageLayout full = sw::page_layout(sw::GpuStorage::full);
    EXPECT_EQ(sw::gpu_bytes(1, 0, full), 256u * 76u + 48u);
    EXPECT_EQ(sw::max_gaussians_within(3u * (256u * 76u + 48u) - 1u, 0, full), 512u);
    const sw::ChunkEntry e = make_chunk(0, 0);
    EXPECT_EQ(sw::nearest_distance(e, {5.0f, 1.0f, 5.0f}), 0.0f);
    EXPECT_FLOAT_EQ(sw::nearest_distance(e, {13.0f, 1.0f, 14.0f}), 5.0f);
    plugin_msgs::LodRule lod;  // smooth transitions or not: a Gaussian is never drawn past its hard switch
    EXPECT_NEAR(sw::level_load_distance(e, 3, kFocal, lod), 60.0, 1e-4);
    EXPECT_NEAR(sw::level_load_distance(e, 1, kFocal, lod), 15.0, 1e-4);
    sw::ChunkEntry ratio = e;
    ratio.levels[1].extent_per_min_coverage_max = 0.1f;  // 2·0.1·100 / 0.5 = 40 > 30
    EXPECT_NEAR(sw::level_load_distance(ratio, 2, kFocal, lod), 40.0, 1e-4);
    ratio.levels[1].extent_per_min_coverage_max = -1.0f;
    EXPECT_TRUE(std::isinf(sw::level_load_distance(ratio, 2, kFocal, lod)));
    ratio.levels[0] = {};
    EXPECT_EQ(sw::level_load_distance(ratio, 1, kFocal, lod), 0.0);
    EXPECT_THROW(sw::level_load_distance(e, 4, kFocal, lod), engine::Error);

    EXPECT_EQ(sw::check_chunk_entry(e), "");
    sw::ChunkEntry bad = e;
    std::swap(bad.prefix_count[0], bad.prefix_count[3]);
    EXPECT_NE(sw::check_chunk_entry(bad).find("not ordered"), std::string::npos);
    bad = e;
    bad.file_bytes += 1;
    EXPECT_NE(sw::check_chunk_entry(bad).find("file bytes"), std::string::npos);
}

TEST(StreamPolicy, AGroupSeenAtAGrazingAngleSpansFewerPixels) {
    sw::ChunkEntry g = make_chunk(0, 0);
    g.depth = 1;
    g.cell_m = 1.0f;
    g.bounds_min = {0.0f, 0.0f, 0.0f};
    g.bounds_max = {20.0f, 2.0f, 20.0f};  // widened by the cell: 21 × 3 × 21, centre (10, 1, 10)
    const double full = 1.0 * kFocal / 90.0;
    // From straight above the box's top is all that shows: the cell's edge, as without foreshortening.
    EXPECT_DOUBLE_EQ(sw::group_cell_pixels(g, {10.0f, 92.0f, 10.0f}, 90.0f, kFocal, 90.0f), full);
    // Level with its centre, along x: a = e_y / e_x = 3 / 21.
    EXPECT_NEAR(sw::group_cell_pixels(g, {-80.0f, 1.0f, 10.0f}, 90.0f, kFocal, 90.0f), full * std::sqrt(3.0 / 21.0),
                1e-9);
    // 45° above, along x: a = (1 + 3 / 21) / √2.
    EXPECT_NEAR(sw::group_cell_pixels(g, {-90.0f, 101.0f, 10.0f}, 90.0f, kFocal, 90.0f),
                full * std::sqrt((1.0 + 3.0 / 21.0) / std::sqrt(2.0)), 1e-6);
    EXPECT_DOUBLE_EQ(sw::group_cell_pixels(g, {-80.0f, 1.0f, 10.0f}, 90.0f, kFocal, 0.0f), full);
    // Below 20°: the same area measured against sin 20°; from 45° above, by the edge.
    EXPECT_NEAR(sw::group_cell_pixels(g, {-80.0f, 1.0f, 10.0f}, 90.0f, kFocal, 20.0f),
                full * std::sqrt(3.0 / 21.0 / std::sin(20.0 * std::numbers::pi / 180.0)), 1e-9);
    EXPECT_DOUBLE_EQ(sw::group_cell_pixels(g, {-90.0f, 101.0f, 10.0f}, 90.0f, kFocal, 20.0f), full);
    // Never more than the edge: a tall group seen from the side (a = 51 / 3) and a box of zero width
    // (one cell each way, a ≥ 1).
    sw::ChunkEntry tall = g;
    tall.bounds_max = {2.0f, 50.0f, 2.0f};
    EXPECT_DOUBLE_EQ(sw::group_cell_pixels(tall, {-89.0f, 25.0f, 1.0f}, 90.0f, kFocal, 90.0f), full);
    sw::ChunkEntry point = g;
    point.bounds_max = point.bounds_min;
    EXPECT_DOUBLE_EQ(sw::group_cell_pixels(point, {-90.0f, 0.0f, 0.0f}, 90.0f, kFocal, 90.0f), full);
    // At or inside the box: never coarse enough.
    EXPECT_TRUE(std::isinf(sw::group_cell_pixels(g, {10.0f, 1.0f, 10.0f}, 0.0f, kFocal, 90.0f)));
}

TEST(ChunkStreamer, FarCameraKeepsOnlyTheCoarsePrefixOfEveryChunk) {
    Harness h(sync_settings());
    h.steps({20.0f, 500.0f, 20.0f}, 3);
    for (std::size_t c = 0; c < h.streamer.chunk_count(); ++c) {
        const sw::ChunkStatus s = h.streamer.chunk_status(c);
        EXPECT_EQ(s.finest_resident_level, 4) << s.id;
        EXPECT_EQ(s.finest_needed_level, 4) << s.id;
        EXPECT_EQ(s.levels[2], sw::LevelState::absent) << s.id;
    }
    EXPECT_EQ(h.streamer.resident_bytes(), 16 * kLevelBytes[4]);
    for (const auto& call : h.sink.calls) EXPECT_EQ(call.level, 4);
    EXPECT_EQ(h.streamer.residency().chunks.resident, 16u);
    EXPECT_EQ(h.streamer.residency().chunks.requested, 0u);
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}

TEST(ChunkStreamer, FinerLevelsLoadAtTheirDistanceCoarseFirstAndUnloadBeyondTheHysteresis) {
    Harness h(sync_settings());
    std::map<std::uint64_t, float> distance_at;  // frame → distance to chunk_0_0
    for (int d = 100; d >= 0; --d) {
        distance_at[h.frame] = static_cast<float>(d);
        h.step(before_chunk_0_0(static_cast<float>(d)));
    }
    h.step(before_chunk_0_0(0.0f));
    EXPECT_EQ(h.status("chunk_0_0").finest_resident_level, 1);
    for (int level = 1; level <= 3; ++level) {
        const auto requested = h.of(StreamEventType::requested, "chunk_0_0", level);
        ASSERT_FALSE(requested.empty()) << level;
        // Requested in the frame the distance first reached the level's load distance.
        EXPECT_EQ(distance_at[requested.front().first], static_cast<float>(kLoadDistance[level])) << level;
    }
    // Coarse before fine, parts in order, never anything released on the way in.
    std::vector<int> order;
    for (const auto& call : h.sink.calls)
        if (call.chunk == "chunk_0_0") order.push_back(call.upload ? call.level : -call.level);
    EXPECT_EQ(order, (std::vector<int>{4, 3, 2, 1}));

    // Leaving: level l goes in the first frame beyond 1.25 · D(l) (unload_delay_frames = 0).
    for (int d = 0; d <= 100; ++d) {
        distance_at[h.frame] = static_cast<float>(d);
        h.step(before_chunk_0_0(static_cast<float>(d)));
    }
    for (int level = 1; level <= 3; ++level) {
        const auto evicted = h.of(StreamEventType::evicted, "chunk_0_0", level);
        ASSERT_EQ(evicted.size(), 1u) << level;
        EXPECT_EQ(distance_at[evicted.front().first], std::floor(1.25 * kLoadDistance[level]) + 1.0) << level;
        EXPECT_EQ(evicted.front().second.message, "no longer needed");
        EXPECT_EQ(evicted.front().second.bytes, kLevelBytes[level]);
    }
    EXPECT_EQ(h.status("chunk_0_0").finest_resident_level, 4);
    EXPECT_TRUE(h.of(StreamEventType::evicted, "", 4).empty());
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}

TEST(ChunkStreamer, HysteresisKeepsALevelWhileTheCameraHoversAtItsLoadDistance) {
    sw::StreamerSettings settings = sync_settings();
    settings.unload_delay_frames = 5;
    Harness h(settings);
    h.steps(before_chunk_0_0(59.0f), 2);
    ASSERT_EQ(h.status("chunk_0_0").levels[2], sw::LevelState::resident);
    for (int k = 0; k < 60; ++k) h.step(before_chunk_0_0(k % 2 ? 55.0f : 74.0f));  // 74 < 1.25 · 60
    h.steps(before_chunk_0_0(74.0f), 20);  // beyond the load distance, within the keep distance: no delay runs
    // Beyond the keep distance but back within the delay: still held.
    for (int k = 0; k < 10; ++k) h.step(before_chunk_0_0(k % 2 ? 59.0f : 90.0f));
    EXPECT_EQ(h.of(StreamEventType::requested, "chunk_0_0", 3).size(), 1u);
    EXPECT_TRUE(h.of(StreamEventType::evicted, "chunk_0_0", 3).empty());
    // Away for good: released in the 6th frame beyond the keep distance.
    const std::uint64_t away = h.frame;
    h.steps(before_chunk_0_0(90.0f), 8);
    const auto evicted = h.of(StreamEventType::evicted, "chunk_0_0", 3);
    ASSERT_EQ(evicted.size(), 1u);
    EXPECT_EQ(evicted.front().first, away + 5);
}

TEST(ChunkStreamer, PerFrameUploadBudgetIsNeverExceededAlongAPath) {
    sw::StreamerSettings settings = sync_settings();
    settings.upload_budget_bytes_per_frame = 20000;  // 78 Gaussians: level 1 (640) arrives in 9 parts
    settings.max_requests_in_flight = 6;
    Harness h(settings);
    for (int k = 0; k <= 200; ++k) {
        const float t = static_cast<float>(k) / 200.0f;
        h.step(glm::vec3(-50.0f, 1.0f, -50.0f) + t * glm::vec3(135.0f, 0.0f, 130.0f));
    }
    h.steps({35.0f, 1.0f, 35.0f}, 150);
    EXPECT_LE(h.max_frame_upload, 20000u);
    EXPECT_LE(h.streamer.stats().max_uploaded_bytes_per_update, 20000u);
    EXPECT_GT(h.streamer.stats().max_uploaded_bytes_per_update, 19000u);  // the budget was the limit
    EXPECT_EQ(h.status("chunk_3_3").finest_resident_level, 1);
    const auto parts = h.of(StreamEventType::uploaded, "chunk_3_3", 1);
    ASSERT_GE(parts.size(), 9u);
    for (std::size_t k = 0; k < 9; ++k)
        EXPECT_EQ(parts[parts.size() - 9 + k].second.message, "part " + std::to_string(k + 1) + "/9");
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}

TEST(ChunkStreamer, MemoryBudgetHoldsAlongAPathAndCoarsestLevelsAreNeverEvictedForFinerOnes) {
    sw::StreamerSettings settings = sync_settings();
    settings.memory_budget_bytes = 16 * kLevelBytes[4] + 4 * kLevelBytes[3] + kLevelBytes[1];
    settings.upload_budget_bytes_per_frame = 60000;
    Harness h(settings);
    for (int k = 0; k <= 300; ++k) {
        const float t = static_cast<float>(k) / 300.0f;
        h.step(glm::vec3(-5.0f, 1.0f, -5.0f) + t * glm::vec3(50.0f, 0.0f, 50.0f));
    }
    EXPECT_LE(h.streamer.stats().peak_resident_bytes, settings.memory_budget_bytes);
    EXPECT_GT(h.streamer.stats().levels_evicted_for_memory, 0u);
    EXPECT_TRUE(h.of(StreamEventType::evicted, "", 4).empty());
    for (std::size_t c = 0; c < h.streamer.chunk_count(); ++c)
        EXPECT_GE(h.streamer.chunk_status(c).finest_resident_level, 1);
    EXPECT_EQ(h.streamer.residency().chunks.resident, 16u);
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}

TEST(ChunkStreamer, LoweringTheMemoryBudgetEvictsSmallestMarginFirstAndCoarsestLast) {
    Harness h(sync_settings());
    const glm::vec3 camera{5.0f, 1.0f, 5.0f};  // inside chunk_0_0: distances 0 … 35 m
    h.steps(camera, 3);
    ASSERT_EQ(h.status("chunk_2_0").finest_resident_level, 1);  // exactly 15 m away
    ASSERT_EQ(h.status("chunk_3_3").finest_resident_level, 3);

    sw::StreamerSettings lower = h.streamer.settings();
    lower.memory_budget_bytes = 16 * kLevelBytes[4];
    h.streamer.set_settings(lower);
    h.events.clear();
    h.step(camera);
    const auto evicted = h.of(StreamEventType::evicted);
    ASSERT_FALSE(evicted.empty());
    double previous_margin = 0.0;
    std::map<std::string, int> last_level;
    for (const auto& [frame, e] : evicted) {
        EXPECT_NE(e.level, 4);
        EXPECT_EQ(e.message, "memory budget");
        const double margin = kLoadDistance[e.level] / std::max(1e-9f, h.status(e.chunk_id).distance);
        EXPECT_GE(margin, previous_margin) << e.chunk_id << " level " << e.level;
        previous_margin = margin;
        EXPECT_GT(e.level, last_level[e.chunk_id]) << "finest first within " << e.chunk_id;
        last_level[e.chunk_id] = e.level;
    }
    EXPECT_EQ(h.streamer.resident_bytes(), 16 * kLevelBytes[4]);

    // Below the coarse prefixes of the whole world: the farthest chunks' level 4 go, nearest stay.
    lower.memory_budget_bytes = 10 * kLevelBytes[4];
    h.streamer.set_settings(lower);
    h.events.clear();
    h.step(camera);
    const auto coarse = h.of(StreamEventType::evicted);
    ASSERT_EQ(coarse.size(), 6u);
    float previous = 1e9f;
    for (const auto& [frame, e] : coarse) {
        const float d = h.status(e.chunk_id).distance;
        EXPECT_LE(d, previous) << e.chunk_id;
        previous = d;
    }
    for (std::size_t c = 0; c < h.streamer.chunk_count(); ++c) {
        const sw::ChunkStatus s = h.streamer.chunk_status(c);
        if (s.finest_resident_level == 4) {
            EXPECT_LE(s.distance, previous) << s.id;
        }
    }
    h.steps(camera, 3);  // stable: nothing reloads that would not fit
    EXPECT_TRUE(h.of(StreamEventType::uploaded).empty());
}

TEST(ChunkStreamer, PublishesItsEventsAndOneResidencyReportPerFrame) {
    engine::MessageBus bus;
    std::vector<StreamEvent> events;
    std::vector<ResidencyReport> reports;
    const auto a = bus.subscribe<StreamEvent>([&](const StreamEvent& e) { events.push_back(e); });
    const auto b = bus.subscribe<ResidencyReport>([&](const ResidencyReport& r) { reports.push_back(r); });
    Harness h(sync_settings(), &bus);
    h.source.missing.insert("chunk_3_3.ply");
    h.steps(before_chunk_0_0(10.0f), 4);
    h.steps(before_chunk_0_0(200.0f), 2);

    ASSERT_EQ(reports.size(), 6u);
    for (std::size_t k = 0; k < reports.size(); ++k) EXPECT_EQ(reports[k].frame_index, k);
    EXPECT_EQ(reports.back().resident_bytes, h.streamer.resident_bytes());
    EXPECT_EQ(reports.back().budget_bytes, h.streamer.settings().memory_budget_bytes);
    EXPECT_EQ(reports.back().chunks.failed, 1u);
    EXPECT_EQ(bus.latest<ResidencyReport>(), h.streamer.residency());
    std::vector<StreamEvent> recorded;
    for (const auto& fe : h.events) recorded.push_back(fe.second);
    EXPECT_EQ(events, recorded);
    std::set<StreamEventType> kinds;
    for (const StreamEvent& e : events) kinds.insert(e.event);
    EXPECT_EQ(kinds.size(), 5u);  // requested, loaded, uploaded, evicted, failed
    EXPECT_EQ(reports[0].chunks.requested, 16u);
}

// The thresholds are the splat pass's: with a bus, the latest LodSettings when the streamer is made and every
// later one from the next update on, so a game never copies them by hand.
TEST(ChunkStreamer, FollowsTheSplatPassesThresholdsOnTheBus) {
    engine::MessageBus bus;
    plugin_msgs::LodSettings lod;
    lod.rule.size_threshold_px = 3.0f;
    lod.rule.rel_min = 0.25f;
    bus.publish(lod);
    Harness h(sync_settings(), &bus);
    EXPECT_EQ(h.streamer.settings().rule.size_threshold_px, 3.0f) << "the latest when made";
    EXPECT_EQ(h.streamer.settings().rule.rel_min, 0.25f);
    const auto close = before_chunk_0_0(10.0f);
    h.steps(close, 2);
    const int needed = h.streamer.chunk_status(0).finest_needed_level;
    // A larger S_T selects fine levels only nearer: the same camera needs coarser levels of chunk 0.
    lod.rule.size_threshold_px = 64.0f;
    bus.publish(lod);
    EXPECT_EQ(h.streamer.settings().rule.size_threshold_px, 64.0f) << "from the next update on";
    h.steps(close, 2);
    EXPECT_GT(h.streamer.chunk_status(0).finest_needed_level, needed);
    // New budgets from the game keep the bus's thresholds, not the copy in the settings given.
    sw::StreamerSettings budgets = sync_settings();
    budgets.rule.size_threshold_px = 1.0f;
    h.streamer.set_settings(budgets);
    EXPECT_EQ(h.streamer.settings().rule.size_threshold_px, 64.0f);
    // Without a bus the settings' own thresholds stay.
    Harness alone(sync_settings());
    EXPECT_EQ(alone.streamer.settings().rule.size_threshold_px, plugin_msgs::LodRule{}.size_threshold_px);
}

TEST(ChunkStreamer, RejectsInvalidSettingsAndViews) {
    FakeSource source;
    RecordingSink sink;
    sw::StreamerSettings settings = sync_settings();
    settings.upload_budget_bytes_per_frame = 100;
    try {
        sw::ChunkStreamer streamer(make_world(), "/world", settings, source, sink);
        FAIL() << "no error";
    } catch (const engine::Error& e) {
        EXPECT_NE(std::string(e.what()).find("below one GPU page (256 bytes"), std::string::npos) << e.what();
    }
    sw::ChunkStreamer streamer(make_world(), "/world", sync_settings(), source, sink);
    sw::StreamerSettings other = sync_settings();
    other.gpu_sh_degree = 0;
    EXPECT_THROW(streamer.set_settings(other), engine::Error);
    other = sync_settings();
    other.gpu_pages = {};  // the GPU scene's page layout cannot change under resident data
    EXPECT_THROW(streamer.set_settings(other), engine::Error);
    other = sync_settings();
    other.unload_distance_factor = 0.5f;
    EXPECT_THROW(streamer.set_settings(other), engine::Error);
    other = sync_settings();
    other.anticipation_updates = -1;
    EXPECT_THROW(streamer.set_settings(other), engine::Error);
    for (const float deg : {-1.0f, 91.0f, NAN}) {
        other = sync_settings();
        other.group_grazing_deg = deg;
        EXPECT_THROW(streamer.set_settings(other), engine::Error) << deg;
    }
    EXPECT_THROW(streamer.update({{NAN, 0.0f, 0.0f}, kFocal, 0}), engine::Error);
    EXPECT_THROW(streamer.update({{0.0f, 0.0f, 0.0f}, 0.0f, 0}), engine::Error);
    EXPECT_THROW(streamer.update({{0.0f, 0.0f, 0.0f}, kFocal, 0, {}, 0.5f}), engine::Error) << "a cut scale below 1";
    EXPECT_THROW(streamer.update({{0.0f, 0.0f, 0.0f}, kFocal, 0, {}, NAN}), engine::Error);
}

TEST(ChunkStreamer, ReleaseAllEmptiesTheSinkFinestFirst) {
    Harness h(sync_settings());
    h.steps({5.0f, 1.0f, 5.0f}, 3);
    ASSERT_GT(h.sink.total, 0u);
    h.streamer.release_all();
    EXPECT_EQ(h.sink.total, 0u);
    EXPECT_EQ(h.streamer.resident_bytes(), 0u);
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}

// With the GPU scene's page layout (the default), parts are whole pages and every byte count the
// sink sees is what the pages cost, so the upload budget bounds the GPU scene's real uploads.
TEST(ChunkStreamer, PagedAccountingSplitsLevelsIntoWholePages) {
    sw::StreamerSettings settings = sync_settings();
    settings.gpu_pages = {};
    const std::uint64_t page = sw::gpu_bytes(1, settings.gpu_sh_degree, settings.gpu_pages);
    settings.upload_budget_bytes_per_frame = page;  // one page per frame
    Harness h(settings);
    h.steps({5.0f, 1.0f, 5.0f}, 200);  // the harness checks budgets and byte counts every frame
    int uploads = 0;
    for (const auto& call : h.sink.calls)
        if (call.upload) {
            ++uploads;
            EXPECT_EQ(call.bytes, page);
        }
    EXPECT_GT(uploads, 4);
    EXPECT_LE(h.max_frame_upload, page);
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}
