#pragma once
// What the chunk streamer does, for the UI, the profiler and tests. A chunk file is ordered by
// stream level (4: selectable from any distance, always resident; 3, 2, 1: needed only within
// shorter and shorter distances), so "level l of a chunk" means its prefix holding stream levels
// 4 down to l.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

#include "plugin_msgs/detail/json_read.h"

namespace plugin_msgs {

enum class StreamEventType {
    requested,  // queued for the background reader
    loaded,     // read and decoded on the CPU, waiting for upload
    uploaded,   // in GPU memory and drawable
    evicted,    // GPU memory released to stay within the budget
    failed,     // reading or decoding failed; `message` says why
};
inline constexpr std::array<std::string_view, 5> kStreamEventTypeNames{"requested", "loaded", "uploaded", "evicted",
                                                                       "failed"};

inline std::string_view to_string(StreamEventType type) {
    return detail::enum_name(kStreamEventTypeNames, type);
}
inline void to_json(nlohmann::json& json, StreamEventType type) {
    json = std::string(to_string(type));
}
inline void from_json(const nlohmann::json& json, StreamEventType& type) {
    type = detail::enum_from_json<StreamEventType>(kStreamEventTypeNames, json);
}

struct StreamEvent {
    static constexpr std::string_view kind = "stream_event";
    static constexpr int kMaxLevel = 4;  // stream levels 1 (needed only close up) to 4 (always resident)

    std::string chunk_id;  // the chunk file's stem, e.g. "chunk_+003_-002"
    StreamEventType event = StreamEventType::requested;
    int level = 0;            // finest stream level concerned (1..4); 0 when the event is about the whole chunk
    std::uint64_t bytes = 0;  // bytes read, uploaded or released by this step
    std::string message;      // the error for `failed`, otherwise free text (may be empty)

    friend bool operator==(const StreamEvent&, const StreamEvent&) = default;
};

inline void to_json(nlohmann::json& json, const StreamEvent& e) {
    json = nlohmann::json{
        {"chunk_id", e.chunk_id}, {"event", e.event}, {"level", e.level}, {"bytes", e.bytes}, {"message", e.message}};
}

inline void from_json(const nlohmann::json& json, StreamEvent& e) {
    constexpr auto kind = StreamEvent::kind;
    detail::require_object(json, kind);
    detail::only_keys(json, kind, {"chunk_id", "event", "level", "bytes", "message"});
    StreamEvent read;
    detail::read(json, kind, "chunk_id", read.chunk_id);
    detail::read(json, kind, "event", read.event);
    detail::read(json, kind, "level", read.level);
    detail::read(json, kind, "bytes", read.bytes);
    detail::read(json, kind, "message", read.message);
    if (read.level < 0 || read.level > StreamEvent::kMaxLevel)
        detail::field_error(kind, "level", "must be 0 (whole chunk) or 1..4, got " + std::to_string(read.level));
    e = std::move(read);
}

// How many chunks are in each state.
struct ChunkStateCounts {
    std::uint32_t requested = 0;  // queued or being read
    std::uint32_t loaded = 0;     // decoded, waiting for upload
    std::uint32_t resident = 0;   // drawable (at least their coarse prefix)
    std::uint32_t failed = 0;

    friend bool operator==(const ChunkStateCounts&, const ChunkStateCounts&) = default;
};

// Published once per frame by the streamer: GPU memory in use against its budget.
struct ResidencyReport {
    static constexpr std::string_view kind = "residency";

    std::uint64_t frame_index = 0;
    std::uint64_t resident_bytes = 0;  // may briefly exceed the budget until evictions catch up
    std::uint64_t budget_bytes = 0;
    ChunkStateCounts chunks;
    ChunkStateCounts groups;         // chunk groups (coarse Gaussians standing for squares of chunks)
    std::uint32_t drawn_chunks = 0;  // chunks and groups the renderer draws this frame: the LOD cut
    std::uint32_t drawn_groups = 0;

    friend bool operator==(const ResidencyReport&, const ResidencyReport&) = default;
};

inline void to_json(nlohmann::json& json, const ChunkStateCounts& c) {
    json = nlohmann::json{
        {"requested", c.requested}, {"loaded", c.loaded}, {"resident", c.resident}, {"failed", c.failed}};
}

inline void from_json(const nlohmann::json& json, ChunkStateCounts& c) {
    constexpr std::string_view kind = "residency.chunks";
    detail::require_object(json, kind);
    detail::only_keys(json, kind, {"requested", "loaded", "resident", "failed"});
    detail::read(json, kind, "requested", c.requested);
    detail::read(json, kind, "loaded", c.loaded);
    detail::read(json, kind, "resident", c.resident);
    detail::read(json, kind, "failed", c.failed);
}

inline void to_json(nlohmann::json& json, const ResidencyReport& r) {
    json = nlohmann::json{{"frame_index", r.frame_index},
                          {"resident_bytes", r.resident_bytes},
                          {"budget_bytes", r.budget_bytes},
                          {"chunks", r.chunks},
                          {"groups", r.groups},
                          {"drawn_chunks", r.drawn_chunks},
                          {"drawn_groups", r.drawn_groups}};
}

inline void from_json(const nlohmann::json& json, ResidencyReport& r) {
    constexpr auto kind = ResidencyReport::kind;
    detail::require_object(json, kind);
    detail::only_keys(
        json, kind,
        {"frame_index", "resident_bytes", "budget_bytes", "chunks", "groups", "drawn_chunks", "drawn_groups"});
    ResidencyReport read;
    detail::read(json, kind, "frame_index", read.frame_index);
    detail::read(json, kind, "resident_bytes", read.resident_bytes);
    detail::read(json, kind, "budget_bytes", read.budget_bytes);
    // The nested reader's message already names "residency.chunks.<key>".
    if (const auto it = json.find("chunks"); it != json.end()) from_json(*it, read.chunks);
    if (const auto it = json.find("groups"); it != json.end()) from_json(*it, read.groups);
    if (json.contains("drawn_chunks")) detail::read(json, kind, "drawn_chunks", read.drawn_chunks);
    if (json.contains("drawn_groups")) detail::read(json, kind, "drawn_groups", read.drawn_groups);
    r = read;
}

}  // namespace plugin_msgs
