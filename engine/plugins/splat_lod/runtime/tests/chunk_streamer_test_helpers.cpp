// The chunk_streamer_test* files' shared world, source, sink and harness (chunk_streamer_test_helpers.h).
#include "chunk_streamer_test_helpers.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "engine/core/error.h"

namespace chunk_streamer_test {
namespace {

using plugin_msgs::StreamEvent;
using plugin_msgs::StreamEventType;

int level_of_record(const sw::ChunkEntry& e, std::uint64_t record) {
    for (int l = 4; l >= 1; --l)
        if (record < e.prefix_count[static_cast<std::size_t>(l - 1)]) return l;
    return 1;
}

}  // namespace

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

void set_stream_level(splat_lod::SplatCloud& cloud, std::size_t i, int level) {
    static const double root_l = std::sqrt(2.0 * std::log(255.0 / (1.0 + std::exp(-2.0))));  // opacity logit 2
    const auto& reach = sw::StreamLevelRule{}.reach_min;                                     // of levels 4, 3, 2
    const double extent =
        level == 4 ? 1.0
        : level == 1
            ? 0.5 * reach[2]
            : std::sqrt(reach[static_cast<std::size_t>(3 - level)] * reach[static_cast<std::size_t>(4 - level)]);
    cloud.lod_level[i] = static_cast<std::uint8_t>(level == 4 ? 4 : 1);
    cloud.opacity_logits[i] = 2.0f;
    cloud.log_scales[i] = glm::vec3(static_cast<float>(std::log(extent / root_l)));
    cloud.coverage_min[i] = 100.0f;
    cloud.coverage_max[i] = 200.0f;
}

splat_lod::SplatCloud FakeSource::read(const std::filesystem::path& file, const sw::ChunkEntry& chunk,
                                       std::uint64_t begin, std::uint64_t end) {
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

void RecordingSink::upload(const sw::LevelPart& p) {
    calls.push_back({true, p.chunk_id, p.level, p.part, p.bytes});
    if (shown.count(p.chunk_id) && shown[p.chunk_id] != p.visible)
        violations.push_back(p.chunk_id + ": a part uploaded with another visibility than last shown");
    shown[p.chunk_id] = p.visible;
    if (throw_on.count(p.chunk_id + "/" + std::to_string(p.level))) throw engine::Error("out of GPU memory (test)");
    const auto key = std::make_pair(p.chunk_id, p.level);
    for (int l = p.level + 1; l <= 4; ++l)
        if (!complete.count({p.chunk_id, l}))
            violations.push_back(p.chunk_id + ": level " + std::to_string(p.level) + " before " + std::to_string(l));
    if (sw::gpu_bytes(p.gaussians->size(), 3, pages) != p.bytes)
        violations.push_back(p.chunk_id + ": bytes disagree with the cloud");
    if (p.first + p.gaussians->size() > p.level_gaussians) violations.push_back(p.chunk_id + ": part beyond its level");
    if (opacity.count(key) && opacity[key] != p.opacity)
        violations.push_back(p.chunk_id + ": a part uploaded with another opacity than its level's");
    if (!(p.opacity >= 0.0f && p.opacity <= 1.0f)) violations.push_back(p.chunk_id + ": opacity outside [0, 1]");
    opacity[key] = p.opacity;
    level_bytes[key] += p.bytes;
    total += p.bytes;
    frame_bytes += p.bytes;
    if (p.completes_level()) complete.insert(key);
}

void RecordingSink::release(const std::string& chunk, int level) {
    calls.push_back({false, chunk, level, 0, 0});
    for (int l = 1; l < level; ++l)
        if (level_bytes.count({chunk, l}))
            violations.push_back(chunk + ": released " + std::to_string(level) + " before " + std::to_string(l));
    const auto key = std::make_pair(chunk, level);
    if (!level_bytes.count(key)) violations.push_back(chunk + ": released a level that was never uploaded");
    total -= level_bytes[key];
    level_bytes.erase(key);
    opacity.erase(key);
    complete.erase(key);
}

void RecordingSink::fade(const std::string& chunk, int level, float value) {
    const auto key = std::make_pair(chunk, level);
    if (!level_bytes.count(key)) violations.push_back(chunk + ": faded a level that is not uploaded");
    if (!(value >= 0.0f && value <= 1.0f)) violations.push_back(chunk + ": opacity outside [0, 1]");
    opacity[key] = value;
}

sw::StreamerSettings sync_settings() {
    sw::StreamerSettings s;
    s.background_thread = false;
    s.gpu_pages = kFullSlots;  // per-Gaussian accounting keeps these tests' arithmetic exact
    s.upload_budget_bytes_per_frame = 1ull << 30;
    s.memory_budget_bytes = 1ull << 30;
    s.max_requests_in_flight = 64;
    s.unload_delay_frames = 0;
    s.group_cell_px = 1.0f;  // the grouped world's switch distances (chunk_streamer_test_groups.cpp) assume 1 px
    return s;
}

Harness::Harness(sw::StreamerSettings settings, engine::MessageBus* bus, sw::WorldManifest world)
    : streamer(std::move(world), "/world", settings, source, sink, bus) {
    sink.pages = settings.gpu_pages;
}

void Harness::step(const glm::vec3& camera, const glm::vec3& velocity, float cut_scale) {
    streamer.update({camera, kFocal, frame++, velocity, cut_scale});
    if (streamer.settings().background_thread) streamer.wait_idle();
    const std::uint64_t uploaded = sink.take_frame_bytes();
    max_frame_upload = std::max(max_frame_upload, uploaded);
    EXPECT_LE(uploaded, streamer.settings().upload_budget_bytes_per_frame) << "frame " << frame - 1;
    EXPECT_LE(streamer.resident_bytes(), streamer.settings().memory_budget_bytes) << "frame " << frame - 1;
    EXPECT_EQ(streamer.resident_bytes(), sink.total) << "frame " << frame - 1;
    for (const StreamEvent& e : streamer.last_events()) events.push_back({frame - 1, e});
}

std::vector<std::pair<std::uint64_t, StreamEvent>> Harness::of(StreamEventType type, const std::string& id,
                                                               int level) const {
    std::vector<std::pair<std::uint64_t, StreamEvent>> out;
    for (const auto& fe : events)
        if (fe.second.event == type && (id.empty() || fe.second.chunk_id == id) &&
            (level == 0 || fe.second.level == level))
            out.push_back(fe);
    return out;
}

}  // namespace chunk_streamer_test
