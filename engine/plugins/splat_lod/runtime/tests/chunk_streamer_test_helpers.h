#pragma once
// Shared by the chunk_streamer_test* files: a small synthetic world of 4×4 chunks of 10 m, each with
// 10 / 40 / 160 / 640 Gaussians in levels 4 / 3 / 2 / 1 and level bounds that make levels 3 / 2 / 1
// needed within 60 / 30 / 15 m at a 100 px focal length; an in-memory source with controllable
// failures and delays that stands for the chunk files, a recording sink for the GPU, and a harness
// that drives a streamer frame by frame.
#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/core/message_bus.h"
#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/msgs/stream_events.h"
#include "splat_lod/stream/chunk_streamer.h"

namespace chunk_streamer_test {

namespace sw = splat_lod::world;

inline constexpr int kGrid = 4;
inline constexpr float kChunkSize = 10.0f;
inline constexpr float kFocal = 100.0f;
inline constexpr std::array<std::uint64_t, 4> kOwnCounts{640, 160, 40, 10};  // levels 1..4
// The streamer tests count full-storage bytes (256 a Gaussian at SH 3), which keeps their arithmetic round.
inline constexpr sw::PageLayout kFullSlots{1, 0, sw::GpuStorage::full};
inline constexpr std::uint64_t kPerGaussian = sw::gpu_bytes_per_gaussian(3, sw::GpuStorage::full);  // 256
inline constexpr std::uint64_t kLevelBytes[5] = {0, 640 * 256, 160 * 256, 40 * 256, 10 * 256};
inline constexpr double kLoadDistance[4] = {0.0, 15.0, 30.0, 60.0};  // levels 1..3

sw::ChunkEntry make_chunk(int i, int j);
sw::WorldManifest make_world();

// Makes Gaussian i of `cloud` one of stream level `level` under the manifest's default rule
// (world/stream_levels.h; S_T 2, S_rel_min 0.5): level 4 as bake level 4 (reach ∞), levels 3 / 2 / 1
// as bake level 1 with S_min 100, whose reach 2·e / min(2, 50) is its extent e, set between the
// level's bounds.
void set_stream_level(splat_lod::SplatCloud& cloud, std::size_t i, int level);

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
                               std::uint64_t end) override;
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
    std::set<std::string> throw_on;     // "chunk/level" keys whose upload throws
    sw::PageLayout pages = kFullSlots;  // the streamer's (set by the harness)

    void upload(const sw::LevelPart& p) override;
    void release(const std::string& chunk, int level) override;
    void show(const std::string& chunk, bool visible) override { shown[chunk] = visible; }
    void fade(const std::string& chunk, int level, float value) override;
    std::uint64_t take_frame_bytes() { return std::exchange(frame_bytes, 0); }
    // Drawn: something of it uploaded and shown (parts arrive with the visibility last shown).
    bool drawn(const std::string& id) const {
        const auto it = shown.find(id);
        return it != shown.end() && it->second && level_bytes.count({id, 4}) > 0;
    }
    // The opacity a node is drawn with: its level 4's last fade when drawn, else 0.
    float drawn_opacity(const std::string& id) const {
        const auto it = opacity.find({id, 4});
        return drawn(id) && it != opacity.end() ? it->second : 0.0f;
    }
    std::map<std::string, bool> shown;
    std::map<std::pair<std::string, int>, float> opacity;  // per uploaded level: the last fade
};

sw::StreamerSettings sync_settings();

// Drives one streamer frame by frame and checks the invariants that must hold after every update.
struct Harness {
    explicit Harness(sw::StreamerSettings settings, engine::MessageBus* bus = nullptr,
                     sw::WorldManifest world = make_world());

    // One update; `velocity`: the camera's motion per update, for the cut's anticipation; `cut_scale`:
    // a splat budget's scale of the chunk-group switch (StreamView::cut_scale).
    void step(const glm::vec3& camera, const glm::vec3& velocity = glm::vec3(0.0f), float cut_scale = 1.0f);
    void steps(const glm::vec3& camera, int n) {
        for (int k = 0; k < n; ++k) step(camera);
    }
    sw::ChunkStatus status(const std::string& id) const { return streamer.chunk_status(*streamer.find_chunk(id)); }
    std::vector<std::pair<std::uint64_t, plugin_msgs::StreamEvent>> of(plugin_msgs::StreamEventType type,
                                                                       const std::string& id = {}, int level = 0) const;

    FakeSource source;
    RecordingSink sink;
    sw::ChunkStreamer streamer;
    std::uint64_t frame = 0;
    std::uint64_t max_frame_upload = 0;
    std::vector<std::pair<std::uint64_t, plugin_msgs::StreamEvent>> events;  // (frame, event)
};

// A camera in the plane y = 1, `d` metres in front of chunk_0_0's −x face.
inline glm::vec3 before_chunk_0_0(float d) {
    return {-d, 1.0f, 5.0f};
}

}  // namespace chunk_streamer_test
