// The chunk streamer (splat_lod/stream/chunk_streamer.h) on a small synthetic world: 4×4 chunks of
// 10 m, each with 10 / 40 / 160 / 640 Gaussians in levels 4 / 3 / 2 / 1 and level bounds that make
// levels 3 / 2 / 1 needed within 60 / 30 / 15 m at a 100 px focal length. An in-memory source with
// controllable failures and delays stands for the chunk files, a recording sink for the GPU; one
// test streams real files written by write_inria_ply through FileChunkSource.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/message_bus.h"
#include "plugin_msgs/splat_statistics.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/stream/chunk_streamer.h"
#include "splat_lod/worldgen/world_groups.h"
#include "test_support.h"

namespace sw = splat_lod::world;
using plugin_msgs::ResidencyReport;
using plugin_msgs::StreamEvent;
using plugin_msgs::StreamEventType;

namespace {

constexpr int kGrid = 4;
constexpr float kChunkSize = 10.0f;
constexpr float kFocal = 100.0f;
constexpr std::array<std::uint64_t, 4> kOwnCounts{640, 160, 40, 10};   // levels 1..4
constexpr std::uint64_t kPerGaussian = sw::gpu_bytes_per_gaussian(3);  // 256
constexpr std::uint64_t kLevelBytes[5] = {0, 640 * 256, 160 * 256, 40 * 256, 10 * 256};
constexpr double kLoadDistance[4] = {0.0, 15.0, 30.0, 60.0};  // levels 1..3

sw::ChunkEntry make_chunk(int i, int j) {
    sw::ChunkEntry e;
    e.cell = {i, j};
    e.id = "chunk_" + std::to_string(i) + "_" + std::to_string(j);
    e.file = e.id + ".ply";
    e.bounds_min = {static_cast<float>(i) * kChunkSize, 0.0f, static_cast<float>(j) * kChunkSize};
    e.bounds_max = e.bounds_min + glm::vec3(kChunkSize, 2.0f, kChunkSize);
    std::uint64_t total = 0;
    for (int l = 4; l >= 1; --l) {
        total += kOwnCounts[static_cast<std::size_t>(l - 1)];
        e.prefix_count[static_cast<std::size_t>(l - 1)] = total;
    }
    // D(l) = 2·extent·f / S_T = extent · 100 at f = 100 px and S_T = 2.
    e.levels[0].extent_max = 0.15f;
    e.levels[1].extent_max = 0.30f;
    e.levels[2].extent_max = 0.60f;
    e.levels[3].extent_max = 1.20f;
    e.header_bytes = 50;
    e.vertex_bytes = 100;
    e.file_bytes = e.prefix_bytes(1);
    return e;
}

sw::WorldManifest make_world() {
    sw::WorldManifest world;
    world.size_m = kGrid * kChunkSize;
    world.chunk_size_m = kChunkSize;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) world.chunks.push_back(make_chunk(i, j));
    return world;
}

// Makes Gaussian i of `cloud` one of stream level `level` under the manifest's default rule
// (world/stream_levels.h; S_T 2, S_rel_min 0.5): level 4 as bake level 4 (reach ∞), levels 3 / 2 / 1
// as bake level 1 with S_min 100, whose reach 2·e / min(2, 50) is its extent e, set between the
// level's bounds.
void set_stream_level(splat_lod::SplatCloud& cloud, std::size_t i, int level) {
    static const double root_l = std::sqrt(2.0 * std::log(255.0 / (1.0 + std::exp(-2.0))));  // opacity logit 2
    const auto& reach = sw::StreamLevelRule{}.reach_min;  // of levels 4, 3, 2
    const double extent = level == 4   ? 1.0
                          : level == 1 ? 0.5 * reach[2]
                                       : std::sqrt(reach[static_cast<std::size_t>(3 - level)] *
                                                   reach[static_cast<std::size_t>(4 - level)]);
    cloud.lod_level[i] = static_cast<std::uint8_t>(level == 4 ? 4 : 1);
    cloud.opacity_logits[i] = 2.0f;
    cloud.log_scales[i] = glm::vec3(static_cast<float>(std::log(extent / root_l)));
    cloud.coverage_min[i] = 100.0f;
    cloud.coverage_max[i] = 200.0f;
}

int level_of_record(const sw::ChunkEntry& e, std::uint64_t record) {
    for (int l = 4; l >= 1; --l)
        if (record < e.prefix_count[static_cast<std::size_t>(l - 1)]) return l;
    return 1;
}

// In-memory chunks. Configure before the streamer starts; only counters change afterwards.
class FakeSource final : public sw::ChunkSource {
public:
    std::set<std::string> missing;                          // file names that "do not exist"
    std::map<std::string, std::uint64_t> truncated_at;      // reads reaching past this record throw
    std::map<std::string, std::uint64_t> wrong_level_from;  // records from here decode as stream level 1
    std::chrono::milliseconds delay{0};
    std::atomic<int> reads{0};
    std::map<std::string, int> reads_per_file;  // synchronous tests only

    splat_lod::SplatCloud read(const std::filesystem::path& file, const sw::ChunkEntry& chunk, std::uint64_t begin,
                               std::uint64_t end) override {
        ++reads;
        if (delay.count() > 0) std::this_thread::sleep_for(delay);
        const std::string name = file.filename().string();
        if (!background) ++reads_per_file[name];
        if (missing.count(name)) engine::fail(file.string() + ": cannot open (No such file or directory)");
        if (auto it = truncated_at.find(name); it != truncated_at.end() && end > it->second)
            engine::fail(file.string() + ": the file ends before record " + std::to_string(end) + " (truncated)");
        splat_lod::SplatCloud cloud;
        cloud.resize(static_cast<std::size_t>(end - begin));
        const auto wrong = wrong_level_from.find(name);
        for (std::uint64_t r = begin; r < end; ++r) {
            const bool corrupt = wrong != wrong_level_from.end() && r >= wrong->second;
            set_stream_level(cloud, static_cast<std::size_t>(r - begin), corrupt ? 1 : level_of_record(chunk, r));
            cloud.positions[static_cast<std::size_t>(r - begin)] = (chunk.bounds_min + chunk.bounds_max) * 0.5f;
        }
        return cloud;
    }
    bool background = false;
};

// Records what the GPU side would hold and checks the sink's contract on every call.
class RecordingSink final : public sw::ResidencySink {
public:
    struct Call {
        bool upload = true;
        std::string chunk;
        int level = 0;
        std::uint32_t part = 0;
        std::uint64_t bytes = 0;
        friend bool operator==(const Call&, const Call&) = default;
    };
    std::vector<Call> calls;
    std::vector<std::string> violations;
    std::map<std::pair<std::string, int>, std::uint64_t> level_bytes;
    std::set<std::pair<std::string, int>> complete;
    std::uint64_t total = 0;
    std::uint64_t frame_bytes = 0;
    std::set<std::string> throw_on;  // "chunk/level" keys whose upload throws
    sw::PageLayout pages{1, 0};      // the streamer's (set by the harness)

    void upload(const sw::LevelPart& p) override {
        calls.push_back({true, p.chunk_id, p.level, p.part, p.bytes});
        if (shown.count(p.chunk_id) && shown[p.chunk_id] != p.visible)
            violations.push_back(p.chunk_id + ": a part uploaded with another visibility than last shown");
        shown[p.chunk_id] = p.visible;
        if (throw_on.count(p.chunk_id + "/" + std::to_string(p.level))) throw engine::Error("out of GPU memory (test)");
        const auto key = std::make_pair(p.chunk_id, p.level);
        for (int l = p.level + 1; l <= 4; ++l)
            if (!complete.count({p.chunk_id, l}))
                violations.push_back(p.chunk_id + ": level " + std::to_string(p.level) + " before " +
                                     std::to_string(l));
        if (sw::gpu_bytes(p.gaussians->size(), 3, pages) != p.bytes)
            violations.push_back(p.chunk_id + ": bytes disagree with the cloud");
        if (p.first + p.gaussians->size() > p.level_gaussians)
            violations.push_back(p.chunk_id + ": part beyond its level");
        level_bytes[key] += p.bytes;
        total += p.bytes;
        frame_bytes += p.bytes;
        if (p.completes_level()) complete.insert(key);
    }
    void release(const std::string& chunk, int level) override {
        calls.push_back({false, chunk, level, 0, 0});
        for (int l = 1; l < level; ++l)
            if (level_bytes.count({chunk, l}))
                violations.push_back(chunk + ": released " + std::to_string(level) + " before " + std::to_string(l));
        const auto key = std::make_pair(chunk, level);
        if (!level_bytes.count(key)) violations.push_back(chunk + ": released a level that was never uploaded");
        total -= level_bytes[key];
        level_bytes.erase(key);
        complete.erase(key);
    }
    void show(const std::string& chunk, bool visible) override { shown[chunk] = visible; }
    std::uint64_t take_frame_bytes() { return std::exchange(frame_bytes, 0); }
    // Drawn: something of it uploaded and shown (parts arrive with the visibility last shown).
    bool drawn(const std::string& id) const {
        const auto it = shown.find(id);
        return it != shown.end() && it->second && level_bytes.count({id, 4}) > 0;
    }
    std::map<std::string, bool> shown;
};

sw::StreamerSettings sync_settings() {
    sw::StreamerSettings s;
    s.background_thread = false;
    s.gpu_pages = {1, 0};  // per-Gaussian accounting keeps these tests' arithmetic exact
    s.upload_budget_bytes_per_frame = 1ull << 30;
    s.memory_budget_bytes = 1ull << 30;
    s.max_requests_in_flight = 64;
    s.unload_delay_frames = 0;
    s.group_cell_px = 1.0f;  // the grouped world's switch distances below assume 1 px
    return s;
}

// Drives one streamer frame by frame and checks the invariants that must hold after every update.
struct Harness {
    explicit Harness(sw::StreamerSettings settings, engine::MessageBus* bus = nullptr,
                     sw::WorldManifest world = make_world())
        : streamer(std::move(world), "/world", settings, source, sink, bus) {
        sink.pages = settings.gpu_pages;
    }

    void step(const glm::vec3& camera) {
        streamer.update({camera, kFocal, frame++});
        if (streamer.settings().background_thread) streamer.wait_idle();
        const std::uint64_t uploaded = sink.take_frame_bytes();
        max_frame_upload = std::max(max_frame_upload, uploaded);
        EXPECT_LE(uploaded, streamer.settings().upload_budget_bytes_per_frame) << "frame " << frame - 1;
        EXPECT_LE(streamer.resident_bytes(), streamer.settings().memory_budget_bytes) << "frame " << frame - 1;
        EXPECT_EQ(streamer.resident_bytes(), sink.total) << "frame " << frame - 1;
        for (const StreamEvent& e : streamer.last_events()) events.push_back({frame - 1, e});
    }
    void steps(const glm::vec3& camera, int n) {
        for (int k = 0; k < n; ++k) step(camera);
    }
    sw::ChunkStatus status(const std::string& id) const { return streamer.chunk_status(*streamer.find_chunk(id)); }
    std::vector<std::pair<std::uint64_t, StreamEvent>> of(StreamEventType type, const std::string& id = {},
                                                          int level = 0) const {
        std::vector<std::pair<std::uint64_t, StreamEvent>> out;
        for (const auto& fe : events)
            if (fe.second.event == type && (id.empty() || fe.second.chunk_id == id) &&
                (level == 0 || fe.second.level == level))
                out.push_back(fe);
        return out;
    }

    FakeSource source;
    RecordingSink sink;
    sw::ChunkStreamer streamer;
    std::uint64_t frame = 0;
    std::uint64_t max_frame_upload = 0;
    std::vector<std::pair<std::uint64_t, StreamEvent>> events;  // (frame, event)
};

// A camera in the plane y = 1, `d` metres in front of chunk_0_0's −x face.
glm::vec3 before_chunk_0_0(float d) {
    return {-d, 1.0f, 5.0f};
}

}  // namespace

TEST(StreamPolicy, GpuBytesDistancesAndLoadDistances) {
    EXPECT_EQ(sw::gpu_bytes(1, 3), 256u);
    EXPECT_EQ(sw::gpu_bytes(10, 0), 760u);
    // As the incremental GPU scene stores uploads: whole pages of 256 slots plus a 48-byte cluster.
    const sw::PageLayout pages;
    EXPECT_EQ(sw::gpu_bytes(0, 0, pages), 0u);
    EXPECT_EQ(sw::gpu_bytes(1, 0, pages), 256u * 76u + 48u);
    EXPECT_EQ(sw::gpu_bytes(300, 0, pages), 2u * (256u * 76u + 48u));
    EXPECT_EQ(sw::max_gaussians_within(3u * (256u * 76u + 48u) - 1u, 0, pages), 512u);
    EXPECT_EQ(sw::max_gaussians_within(100u, 0, pages), 0u);
    const sw::ChunkEntry e = make_chunk(0, 0);
    EXPECT_EQ(sw::nearest_distance(e, {5.0f, 1.0f, 5.0f}), 0.0f);
    EXPECT_FLOAT_EQ(sw::nearest_distance(e, {13.0f, 1.0f, 14.0f}), 5.0f);
    const sw::LodThresholds lod;
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
    EXPECT_THROW(streamer.update({{NAN, 0.0f, 0.0f}, kFocal, 0}), engine::Error);
    EXPECT_THROW(streamer.update({{0.0f, 0.0f, 0.0f}, 0.0f, 0}), engine::Error);
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
    EXPECT_EQ(near.resident_bytes, sw::gpu_bytes(30, 3));
    const sw::ChunkStatus broken = streamer.chunk_status(1);
    EXPECT_TRUE(broken.failed);
    EXPECT_EQ(broken.finest_resident_level, 0);
    EXPECT_NE(broken.failure.find("chunk_1.ply"), std::string::npos) << broken.failure;
    EXPECT_EQ(std::count_if(events.begin(), events.end(),
                            [](const StreamEvent& e) { return e.event == StreamEventType::failed; }),
              1);
    EXPECT_TRUE(sink.violations.empty()) << sink.violations.front();
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

namespace {

// make_world() with chunk groups: 2 × 2 groups of depth 1 (cells of 0.5 m: drawn from 50 m at
// f = 100 px and 1 px) and a root of depth 2 (1 m cells: from 100 m), 30 Gaussians each, all of
// stream level 4.
sw::WorldManifest make_grouped_world() {
    sw::WorldManifest world = make_world();
    const int count = sw::chunks_per_side(world);
    for (sw::ChunkEntry& c : world.chunks) c.cell -= glm::ivec2(count / 2);  // cells from −count/2, as generated
    for (int depth = 1; depth <= 2; ++depth) {
        std::set<std::pair<int, int>> made;
        for (const sw::ChunkEntry& c : world.chunks) {
            const glm::ivec2 g = sw::group_of_chunk(c.cell, count, depth);
            if (!made.insert({g.x, g.y}).second) continue;
            sw::ChunkEntry e = c;
            e.id = sw::group_id(depth, g);
            e.file = e.id + ".ply";
            e.cell = g;
            e.depth = depth;
            e.cell_m = depth == 1 ? 0.5f : 1.0f;
            e.bounds_min = glm::vec3(1e9f);
            e.bounds_max = glm::vec3(-1e9f);
            for (const sw::ChunkEntry& m : world.chunks)
                if (sw::group_of_chunk(m.cell, count, depth) == g) {
                    e.bounds_min = glm::min(e.bounds_min, m.bounds_min);
                    e.bounds_max = glm::max(e.bounds_max, m.bounds_max);
                }
            e.prefix_count = {30, 30, 30, 30};
            e.levels = {};
            e.file_bytes = e.prefix_bytes(1);
            world.groups.push_back(e);
        }
    }
    return world;
}

// Over every chunk, how many nodes on its path to the root are drawn: exactly one means no hole and
// nothing drawn twice over the same ground.
std::vector<std::string> coverage_problems(const Harness& h, const sw::WorldManifest& world) {
    std::vector<std::string> problems;
    const int count = sw::chunks_per_side(world);
    for (const sw::ChunkEntry& c : world.chunks) {
        int drawn = h.sink.drawn(c.id) ? 1 : 0;
        for (int depth = 1; depth <= 2; ++depth) drawn += h.sink.drawn(sw::group_id(depth, sw::group_of_chunk(c.cell, count, depth))) ? 1 : 0;
        if (drawn != 1) problems.push_back(c.id + " is drawn " + std::to_string(drawn) + " times");
    }
    return problems;
}

}  // namespace

TEST(ChunkStreamerGroups, FarViewLoadsTheRootOnly) {
    Harness h(sync_settings(), nullptr, make_grouped_world());
    h.steps({20.0f, 400.0f, 20.0f}, 4);
    EXPECT_TRUE(h.sink.drawn("group_2_+000_+000"));
    EXPECT_EQ(h.sink.total, 30u * kPerGaussian) << "only the root is resident";
    EXPECT_EQ(h.streamer.residency().drawn_groups, 1u);
    EXPECT_EQ(h.streamer.residency().drawn_chunks, 0u);
    EXPECT_TRUE(h.status("group_2_+000_+000").in_cut);
    EXPECT_FALSE(h.status("chunk_0_0").in_cut);
    EXPECT_TRUE(h.sink.violations.empty());
    EXPECT_TRUE(coverage_problems(h, make_grouped_world()).empty());
}

TEST(ChunkStreamerGroups, FlyingInAndOutNeverLeavesAHoleOrDrawsTwice) {
    sw::StreamerSettings settings = sync_settings();
    settings.upload_budget_bytes_per_frame = 200 * kPerGaussian;  // levels arrive over several frames
    settings.unload_delay_frames = 3;
    const sw::WorldManifest world = make_grouped_world();
    Harness h(settings, nullptr, world);
    glm::vec3 eye{20.0f, 400.0f, 20.0f};
    h.steps(eye, 3);
    std::set<std::string> seen_drawn;
    for (int k = 0; k < 160; ++k) {  // down to the ground in the corner chunk and back up
        const float t = k < 80 ? static_cast<float>(k) / 79.0f : static_cast<float>(159 - k) / 79.0f;
        eye = glm::mix(glm::vec3(20.0f, 400.0f, 20.0f), glm::vec3(2.0f, 1.5f, 2.0f), std::pow(t, 0.4f));
        h.step(eye);
        for (const std::string& problem : coverage_problems(h, world)) ADD_FAILURE() << "step " << k << ": " << problem;
        for (const auto& [id, visible] : h.sink.shown)
            if (h.sink.drawn(id)) seen_drawn.insert(id);
    }
    EXPECT_TRUE(seen_drawn.count("chunk_0_0"));
    EXPECT_TRUE(seen_drawn.count("group_1_+001_+001"));
    EXPECT_TRUE(seen_drawn.count("group_1_+000_+000"));
    EXPECT_TRUE(seen_drawn.count("group_2_+000_+000"));
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}

TEST(ChunkStreamerGroups, NearViewDrawsChunksAndReleasesGroups) {
    sw::StreamerSettings settings = sync_settings();
    Harness h(settings, nullptr, make_grouped_world());
    h.steps({20.0f, 400.0f, 20.0f}, 3);
    h.steps({5.0f, 1.0f, 5.0f}, 6);  // inside chunk_0_0: its group 1 is 0 m away
    EXPECT_TRUE(h.sink.drawn("chunk_0_0"));
    EXPECT_FALSE(h.sink.drawn("group_2_+000_+000"));
    EXPECT_EQ(h.sink.level_bytes.count({"group_2_+000_+000", 4}), 0u) << "released once replaced";
    // Chunks more than 50 m away are drawn from their depth-1 group... none here (the world is 40 m):
    EXPECT_EQ(h.streamer.residency().drawn_groups, 0u);
    EXPECT_EQ(h.streamer.residency().drawn_chunks, 16u);
}

TEST(ChunkStreamerGroups, AMissingGroupIsReportedAndItsChunksDrawn) {
    Harness h(sync_settings(), nullptr, make_grouped_world());
    h.source.missing.insert("group_2_+000_+000.ply");
    h.steps({20.0f, 400.0f, 20.0f}, 6);
    const auto failed = h.of(StreamEventType::failed, "group_2_+000_+000");
    ASSERT_EQ(failed.size(), 1u);
    EXPECT_NE(failed[0].second.message.find("group_2_+000_+000.ply"), std::string::npos);
    EXPECT_FALSE(h.sink.drawn("group_2_+000_+000"));
    EXPECT_EQ(h.streamer.residency().drawn_groups, 4u) << "the depth-1 groups stand in for the root";
    EXPECT_TRUE(coverage_problems(h, make_grouped_world()).empty());
}

TEST(ChunkStreamerGroups, GroupsOffStreamsChunksOnly) {
    sw::StreamerSettings settings = sync_settings();
    settings.group_cell_px = 0.0f;
    Harness h(settings, nullptr, make_grouped_world());
    h.steps({20.0f, 400.0f, 20.0f}, 4);
    EXPECT_EQ(h.streamer.residency().drawn_chunks, 16u);
    EXPECT_EQ(h.streamer.residency().groups.resident, 0u);
    for (const auto& [key, bytes] : h.sink.level_bytes) EXPECT_EQ(key.first.rfind("chunk_", 0), 0u) << key.first;
}

TEST(ChunkStreamerGroups, MemoryBudgetHoldsWhileTheCutMoves) {
    sw::StreamerSettings settings = sync_settings();
    settings.memory_budget_bytes = 4 * (10 + 40) * kPerGaussian + 60 * kPerGaussian;
    settings.upload_budget_bytes_per_frame = 100 * kPerGaussian;
    Harness h(settings, nullptr, make_grouped_world());
    for (int k = 0; k < 60; ++k)
        h.step(glm::mix(glm::vec3(20.0f, 400.0f, 20.0f), glm::vec3(5.0f, 2.0f, 5.0f), static_cast<float>(k) / 59.0f));
    EXPECT_TRUE(h.sink.violations.empty());
    EXPECT_GT(h.streamer.residency().drawn_chunks, 0u);
}

TEST(ChunkStreamerGroups, ABindingSplatBudgetMakesTheCutCoarser) {
    EXPECT_EQ(sw::next_group_cell_scale(1.0f, 500, 0), 1.0f) << "no budget";
    EXPECT_EQ(sw::next_group_cell_scale(1.0f, 150, 200), 1.0f) << "within the budget, at 1";
    EXPECT_NEAR(sw::next_group_cell_scale(1.0f, 210, 200), std::sqrt(210.0f / 200.0f), 1e-6f);
    EXPECT_NEAR(sw::next_group_cell_scale(1.0f, 2000, 200), std::exp2(0.25f), 1e-6f) << "at most 2^(1/4) a step";
    EXPECT_EQ(sw::next_group_cell_scale(3.0f, 180, 200), 3.0f) << "between 70 % and 100 %: held";
    EXPECT_NEAR(sw::next_group_cell_scale(3.0f, 100, 200), 3.0f / std::exp2(0.125f), 1e-6f);
    EXPECT_EQ(sw::next_group_cell_scale(1.01f, 0, 200), 1.0f);

    // 60 m above the middle of the world (the boxes 60 m away): the depth-1 groups (0.5 m cells,
    // 0.83 px) are the cut at 1 px, the root (1 m cells, 1.67 px) once the switch is scaled by 2. The
    // renderer's statistics reach the streamer on the bus: a budget drawn 4× over scales it by √4 = 2
    // in steps of at most 2^(1/4).
    engine::MessageBus bus;
    Harness h(sync_settings(), &bus, make_grouped_world());
    h.steps({20.0f, 62.0f, 20.0f}, 4);
    EXPECT_EQ(h.streamer.residency().drawn_groups, 4u);
    EXPECT_EQ(h.streamer.group_cell_scale(), 1.0f);
    plugin_msgs::SplatStatistics over;
    over.splat_budget = 100;
    over.unbudgeted = 400;
    for (int k = 0; k < 4; ++k) {
        bus.publish(over);
        h.step({20.0f, 62.0f, 20.0f});
    }
    EXPECT_NEAR(h.streamer.group_cell_scale(), 2.0f, 1e-5f);
    h.steps({20.0f, 62.0f, 20.0f}, 3);  // no new statistics: the scale holds
    EXPECT_NEAR(h.streamer.group_cell_scale(), 2.0f, 1e-5f);
    EXPECT_TRUE(h.status("group_2_+000_+000").in_cut);
    EXPECT_TRUE(h.sink.drawn("group_2_+000_+000"));
    EXPECT_EQ(h.streamer.residency().drawn_groups, 1u);
}
