#pragma once
// The "Streaming" panel of the game's ImGui overlay: chunks per state, resident GPU memory against
// the memory budget, this frame's upload against the upload budget, chunk failures (id and
// message, from the streamer's `failed` events on the bus), and a graph of the last frame times.
// The budgets can be edited; an edit is handed to the game (which gives it to the streamer).
// Recording is GL- and ImGui-free, so the panel's numbers are unit-tested.
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "splat_lod/msgs/stream_events.h"

#include "engine/core/message_bus.h"
#include "sample_game/chunk_census.h"

namespace sample_game {

struct StreamingSnapshot {
    ChunkCensus chunks;
    std::size_t chunk_count = 0;
    std::uint64_t resident_bytes = 0, memory_budget_bytes = 0;
    std::uint64_t upload_bytes = 0, upload_budget_bytes = 0;
    double frame_ms = 0.0;  // the whole frame: streaming update, render, overlay
    // The LOD cut (docs/world_lod.md): chunks and chunk groups drawn, groups in the world and resident.
    std::uint32_t chunks_drawn = 0, groups_drawn = 0, groups_resident = 0;
    std::size_t group_count = 0;
};

class StreamingPanel {
public:
    static constexpr const char* title = "Streaming";
    static constexpr std::size_t kHistory = 240;  // frames in the graph
    static constexpr std::size_t kFailuresKept = 8;

    // Subscribes to plugin_msgs::StreamEvent on `bus` for the failures.
    explicit StreamingPanel(engine::MessageBus& bus);

    void record(const StreamingSnapshot& snapshot);
    // Draws the widgets (inside an ImGui window, with the overlay's context current). Returns true
    // when the user changed a budget; the new values are then in `memory_budget_mib` / `upload_budget_mib`.
    bool draw(int& memory_budget_mib, float& upload_budget_mib);

    const StreamingSnapshot& latest() const { return latest_; }
    const std::deque<float>& frame_ms() const { return frame_ms_; }
    struct Failure {
        std::string chunk_id;
        std::string message;
    };
    const std::deque<Failure>& failures() const { return failures_; }  // newest last
    std::uint64_t failures_seen() const { return failures_seen_; }

private:
    StreamingSnapshot latest_;
    std::deque<float> frame_ms_;
    std::deque<Failure> failures_;
    std::uint64_t failures_seen_ = 0;
    engine::Subscription events_;
};

}  // namespace sample_game
