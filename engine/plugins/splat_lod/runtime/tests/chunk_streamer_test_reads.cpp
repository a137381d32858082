// The chunk streamer (splat_lod/stream/chunk_streamer.h) when reads fail or run in the background, on
// the small synthetic world of chunk_streamer_test_helpers.h: missing, truncated and corrupt chunks,
// impossible manifest entries and failed uploads reported once and retried, the background reader
// against synchronous reads, cancelled reads and shutdown with reads in flight, and real files written
// by write_inria_ply streamed through FileChunkSource.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "chunk_streamer_test_helpers.h"
#include "engine/core/message_bus.h"
#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/msgs/stream_events.h"
#include "splat_lod/stream/chunk_streamer.h"
#include "test_support.h"

namespace sw = splat_lod::world;
using namespace chunk_streamer_test;
using plugin_msgs::StreamEvent;
using plugin_msgs::StreamEventType;

TEST(ChunkStreamer, MissingTruncatedAndCorruptChunksAreReportedOnceAndSkipped) {
    engine::MessageBus bus;
    std::vector<StreamEvent> failures;
    const auto sub = bus.subscribe<StreamEvent>([&](const StreamEvent& e) {
        if (e.event == StreamEventType::failed) failures.push_back(e);
    });
    Harness h(sync_settings(), &bus);
    h.source.missing.insert("chunk_1_1.ply");
    h.source.truncated_at["chunk_2_2.ply"] = 60;      // inside level 2
    h.source.wrong_level_from["chunk_3_3.ply"] = 12;  // stream level 3 records decode as stream level 1
    h.steps({20.0f, 1.0f, 20.0f}, 30);

    ASSERT_EQ(failures.size(), 3u);
    std::map<std::string, StreamEvent> by_chunk;
    for (const StreamEvent& e : failures) by_chunk[e.chunk_id] = e;
    EXPECT_EQ(by_chunk["chunk_1_1"].level, 4);
    EXPECT_NE(by_chunk["chunk_1_1"].message.find("/world/chunk_1_1.ply"), std::string::npos);
    EXPECT_NE(by_chunk["chunk_1_1"].message.find("cannot open"), std::string::npos);
    EXPECT_EQ(by_chunk["chunk_2_2"].level, 2);
    EXPECT_NE(by_chunk["chunk_2_2"].message.find("truncated"), std::string::npos);
    EXPECT_EQ(by_chunk["chunk_3_3"].level, 3);
    EXPECT_NE(by_chunk["chunk_3_3"].message.find("/world/chunk_3_3.ply"), std::string::npos);
    EXPECT_NE(by_chunk["chunk_3_3"].message.find("record 12 has stream level 1"), std::string::npos);

    EXPECT_EQ(h.status("chunk_1_1").finest_resident_level, 0);
    EXPECT_EQ(h.status("chunk_2_2").finest_resident_level, 3);  // what was read before the failure stays
    EXPECT_EQ(h.status("chunk_3_3").finest_resident_level, 4);
    EXPECT_TRUE(h.status("chunk_2_2").failed);
    EXPECT_EQ(h.source.reads_per_file["chunk_1_1.ply"], 4);  // levels 4..1 requested in frame 0, none since
    for (const char* id : {"chunk_0_0", "chunk_1_2", "chunk_2_1"})
        EXPECT_EQ(h.status(id).finest_resident_level, 1) << id;
    EXPECT_EQ(h.streamer.residency().chunks.failed, 3u);
    EXPECT_EQ(h.streamer.residency().chunks.resident, 15u);
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}

// Compressed chunks give their Gaussians back quantised, so one may land in another stream level than
// the one it is filed under: accepted while the level's manifest bounds hold for it (what the streaming
// decisions use), reported like any failed read when they do not.
TEST(ChunkStreamer, CompressedChunksAreCheckedAgainstTheirLevelBounds) {
    engine::MessageBus bus;
    std::vector<StreamEvent> failures;
    const auto sub = bus.subscribe<StreamEvent>([&](const StreamEvent& e) {
        if (e.event == StreamEventType::failed) failures.push_back(e);
    });
    sw::WorldManifest world = make_world();
    for (sw::ChunkEntry& c : world.chunks) {
        c.codec = sw::ChunkCodec::compact;
        c.vertex_bytes = 0;
        // Bounds that hold for every fake Gaussian (extents up to 1.18, coverage_min 100), so that every
        // level is needed near the camera and records of another stream level pass.
        for (sw::ChunkLevel& level : c.levels) level = {1.25f, 0.0125f};
        if (c.id == "chunk_2_2") c.levels[3].extent_max = 0.05f;  // below its stream level 4 Gaussians
    }
    Harness h(sync_settings(), &bus, world);
    h.source.wrong_level_from["chunk_3_3.ply"] = 12;  // stream level 3 records that decode as stream level 1
    h.steps({20.0f, 1.0f, 20.0f}, 30);

    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(failures[0].chunk_id, "chunk_2_2");
    EXPECT_EQ(failures[0].level, 4);
    EXPECT_NE(failures[0].message.find("outside the bounds the manifest gives stream level 4"), std::string::npos)
        << failures[0].message;
    EXPECT_EQ(h.status("chunk_3_3").finest_resident_level, 1) << "within its level's bounds: drawn";
    EXPECT_TRUE(h.status("chunk_2_2").failed);
}

TEST(ChunkStreamer, AFailedChunkIsRetriedAfterTheConfiguredFrames) {
    sw::StreamerSettings settings = sync_settings();
    settings.retry_failed_after_frames = 10;
    Harness h(settings);
    h.source.missing.insert("chunk_0_0.ply");
    h.steps({500.0f, 1.0f, 500.0f}, 25);
    const auto failed = h.of(StreamEventType::failed, "chunk_0_0");
    ASSERT_EQ(failed.size(), 3u);
    EXPECT_EQ(failed[0].first, 1u);
    EXPECT_EQ(failed[1].first, 12u);
    EXPECT_EQ(failed[2].first, 23u);
    h.source.missing.clear();  // the file appears
    h.steps({500.0f, 1.0f, 500.0f}, 12);
    EXPECT_EQ(h.status("chunk_0_0").finest_resident_level, 4);
    EXPECT_FALSE(h.status("chunk_0_0").failed);
}

TEST(ChunkStreamer, ManifestEntriesThatCannotBeRightFailWithoutReading) {
    sw::WorldManifest world = make_world();
    std::swap(world.chunks[5].prefix_count[0], world.chunks[5].prefix_count[2]);
    Harness h(sync_settings(), nullptr, world);
    h.steps({20.0f, 500.0f, 20.0f}, 3);
    const auto failed = h.of(StreamEventType::failed);
    ASSERT_EQ(failed.size(), 1u);
    EXPECT_EQ(failed[0].second.chunk_id, world.chunks[5].id);
    EXPECT_NE(failed[0].second.message.find("not ordered"), std::string::npos);
    EXPECT_EQ(h.source.reads_per_file.count(world.chunks[5].id + ".ply"), 0u);
    EXPECT_EQ(h.streamer.residency().chunks.resident, 15u);
}

TEST(ChunkStreamer, AnUploadThatThrowsFailsOnlyThatChunk) {
    Harness h(sync_settings());
    h.sink.throw_on.insert("chunk_1_0/3");
    h.steps({5.0f, 1.0f, 5.0f}, 5);
    const auto failed = h.of(StreamEventType::failed);
    ASSERT_EQ(failed.size(), 1u);
    EXPECT_NE(failed[0].second.message.find("upload failed: out of GPU memory"), std::string::npos);
    EXPECT_EQ(h.status("chunk_1_0").finest_resident_level, 4);
    EXPECT_EQ(h.status("chunk_0_1").finest_resident_level, 1);
}

TEST(ChunkStreamer, TheBackgroundReaderReachesTheSameStatesAsSynchronousReads) {
    auto run = [](bool background) {
        sw::StreamerSettings settings = sync_settings();
        settings.background_thread = background;
        settings.upload_budget_bytes_per_frame = 50000;
        settings.max_requests_in_flight = 4;
        Harness h(settings);
        h.source.background = background;
        h.source.missing.insert("chunk_2_1.ply");
        for (int k = 0; k <= 60; ++k) h.step(glm::vec3(-20.0f + static_cast<float>(k), 1.0f, 15.0f));
        return h.sink.calls;
    };
    const auto synchronous = run(false);
    const auto threaded = run(true);
    EXPECT_EQ(threaded, synchronous);
    EXPECT_GT(synchronous.size(), 16u);
}

TEST(ChunkStreamer, ResultsOfLevelsCancelledWhileBeingReadAreDiscarded) {
    sw::StreamerSettings settings = sync_settings();
    settings.background_thread = true;
    Harness h(settings);
    h.source.background = true;
    h.steps({500.0f, 1.0f, 500.0f}, 2);  // coarse prefixes resident
    h.step(before_chunk_0_0(10.0f));     // levels 3..1 of near chunks requested and read
    h.step(before_chunk_0_0(500.0f));    // ... and no longer wanted before their upload
    EXPECT_GT(h.streamer.stats().reads_discarded, 0u);
    for (const auto& call : h.sink.calls) EXPECT_EQ(call.level, 4);
    EXPECT_TRUE(h.of(StreamEventType::uploaded, "", 3).empty());
}

TEST(ChunkStreamer, ShutsDownPromptlyWithReadsInFlight) {
    FakeSource source;
    source.background = true;
    source.delay = std::chrono::milliseconds(40);
    RecordingSink sink;
    sw::StreamerSettings settings = sync_settings();
    settings.background_thread = true;
    settings.max_requests_in_flight = 16;
    const auto start = std::chrono::steady_clock::now();
    {
        sw::ChunkStreamer streamer(make_world(), "/world", settings, source, sink);
        streamer.update({{20.0f, 1.0f, 20.0f}, kFocal, 0});  // 16 reads queued
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    const auto elapsed = std::chrono::steady_clock::now() - start;
    EXPECT_LT(elapsed, std::chrono::milliseconds(250));  // 16 reads would take 640 ms
    EXPECT_LE(source.reads.load(), 2);
    EXPECT_TRUE(sink.calls.empty());
}

TEST(ChunkStreamer, StreamsRealChunkFilesAndReportsATruncatedOne) {
    const std::filesystem::path folder = engine::test::output_dir("chunk_streamer");
    sw::WorldManifest world;
    for (int i = 0; i < 2; ++i) {
        splat_lod::SplatCloud cloud;
        cloud.resize(30);
        for (std::size_t g = 0; g < cloud.size(); ++g) {
            set_stream_level(cloud, g, g < 3 ? 4 : g < 8 ? 3 : g < 15 ? 2 : 1);
            cloud.positions[g] = {static_cast<float>(i) * 10.0f + static_cast<float>(g) * 0.3f, 0.0f, 0.0f};
        }
        const std::string file = "chunk_" + std::to_string(i) + ".ply";
        splat_lod::write_inria_ply(folder / file, cloud);
        world.chunks.push_back(sw::describe_chunk(cloud, folder, file, {i, 0}, world.stream_levels));
        EXPECT_EQ(world.chunks.back().prefix_count, (std::array<std::uint64_t, 4>{30, 15, 8, 3}));
    }
    // Chunk 1 loses its last 10 bytes after the manifest was written.
    const std::filesystem::path truncated = folder / "chunk_1.ply";
    std::filesystem::resize_file(truncated, std::filesystem::file_size(truncated) - 10);

    sw::FileChunkSource source;
    RecordingSink sink;
    sw::StreamerSettings settings = sync_settings();
    sw::ChunkStreamer streamer(world, folder, settings, source, sink);
    std::vector<StreamEvent> events;
    for (std::uint64_t f = 0; f < 6; ++f) {
        streamer.update({{0.0f, 0.5f, 0.0f}, kFocal, f});
        events.insert(events.end(), streamer.last_events().begin(), streamer.last_events().end());
    }
    const sw::ChunkStatus near = streamer.chunk_status(0);
    EXPECT_EQ(near.finest_resident_level, 1);
    EXPECT_EQ(near.resident_bytes, sw::gpu_bytes(30, 3, kFullSlots));
    const sw::ChunkStatus broken = streamer.chunk_status(1);
    EXPECT_TRUE(broken.failed);
    EXPECT_EQ(broken.finest_resident_level, 0);
    EXPECT_NE(broken.failure.find("chunk_1.ply"), std::string::npos) << broken.failure;
    EXPECT_EQ(std::count_if(events.begin(), events.end(),
                            [](const StreamEvent& e) { return e.event == StreamEventType::failed; }),
              1);
    EXPECT_TRUE(sink.violations.empty()) << sink.violations.front();
}
