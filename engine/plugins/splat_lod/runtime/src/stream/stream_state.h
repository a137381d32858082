#pragma once
// The chunk streamer's private state (chunk_streamer.h), shared by chunk_streamer.cpp (the frame's
// steps that move data) and stream_plan.cpp (what is wanted, in which order, and what to evict).
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "splat_lod/stream/chunk_streamer.h"
#include "splat_lod/stream/stream_reader.h"

namespace splat_lod::world {

enum class PartPhase : std::uint8_t { idle, requested, loaded, uploaded };

struct PartSlot {
    PartPhase phase = PartPhase::idle;
    std::uint64_t first = 0;  // offset within the level
    std::uint64_t count = 0;
    std::shared_ptr<const SplatCloud> gaussians;  // while loaded
    std::uint64_t bytes = 0;                      // GPU bytes once loaded
};

struct LevelSlot {
    std::uint64_t begin = 0, end = 0;  // the level's Gaussians in the chunk file
    std::uint64_t planned_bytes = 0;   // GPU bytes of the whole level
    std::vector<PartSlot> parts;       // empty for an empty level
    std::uint64_t generation = 0;      // bumped on cancellation: older read results are stale
    std::uint64_t resident_bytes = 0;  // GPU bytes of the uploaded parts
    double margin = 0.0;               // m_pref: load distance / distance, over this and finer levels
    int frames_outside_keep = 0;       // consecutive updates beyond the unload distance while active
    bool wanted = false;               // needed, or loaded and held by hysteresis
    bool target = false;               // wanted and within the memory budget's plan
    float fade = 0.0f;                 // the level's own fade-in while its node is on screen (stream_fade.cpp)
    float told = -1.0f;                // the opacity the sink was last given (ResidencySink::fade); −1: none

    bool active() const;    // some part requested, loaded or uploaded
    bool complete() const;  // every part uploaded (an empty level always is)
    bool any_uploaded() const;
    std::size_t parts_in(PartPhase phase) const;
};

struct ChunkSlot {
    const ChunkEntry* entry = nullptr;
    std::filesystem::path file;  // manifest folder / entry->file
    std::array<LevelSlot, kLevels> levels;
    float distance = 0.0f;
    float cut_distance = 0.0f;  // what the cut decides by: the farther of now and ahead ("anticipation")
    int finest_needed = kLevels;
    bool failed = false;
    bool failure_permanent = false;  // the manifest entry itself is wrong
    int failed_level = 0;            // levels ≤ this are not loaded while failed
    std::uint64_t failed_frame = 0;
    std::string failure;
    // The quadtree of chunk groups (chunk_streamer.h, "the cut"); chunks have depth 0.
    int depth = 0;
    std::size_t parent = kNoSlot;
    std::vector<std::size_t> children;
    bool in_cut = false;
    bool near_cut = false;  // in the cut of a camera unload_distance_factor times nearer or farther
    bool drawn = false;     // decided after this update's uploads
    bool shown = false;     // what the sink was last told (ResidencySink::show): on screen
    float fade = 0.0f;      // the node's opacity: toward 1 while drawn, toward 0 after (stream_fade.cpp)

    std::uint64_t visited = 0;  // State::stamp of the last update whose work list holds it

    bool on_screen() const { return drawn || fade > 0.0f; }

    static constexpr std::size_t kNoSlot = static_cast<std::size_t>(-1);
    LevelSlot& level(int l) { return levels[static_cast<std::size_t>(l - 1)]; }
    const LevelSlot& level(int l) const { return levels[static_cast<std::size_t>(l - 1)]; }
    bool blocked(int l) const { return failed && l <= failed_level; }
};

// Importance of one level of one chunk: smaller ranks first (loading), larger ranks are evicted
// first. Level 4 of every chunk (by distance) before any finer level (by margin, largest first).
struct LevelRank {
    int tier = 0;          // 0: the coarsest level of a node in the cut, 1: finer levels, 2: level 4 outside the cut
    double primary = 0.0;  // tier 0: distance; tier 1: −margin
    double distance = 0.0;
    int coarseness = 0;  // −level: coarser first on ties
    std::size_t chunk = 0;

    bool operator<(const LevelRank& o) const;
};

struct PlannedLevel {
    LevelRank rank;
    std::size_t chunk = 0;
    int level = kLevels;
};

enum class DropReason { unneeded, memory, outranked, failure, release_all, resplit };

struct ChunkStreamer::State {
    State(WorldManifest world, std::filesystem::path root, StreamerSettings s, ChunkSource& src, ResidencySink& snk,
          engine::MessageBus* message_bus);

    WorldManifest manifest;
    std::filesystem::path folder;
    StreamerSettings settings;
    std::optional<StreamerSettings> pending_settings;
    ResidencySink& sink;
    engine::MessageBus* bus;
    std::vector<ChunkSlot> chunks;    // the manifest's chunks, then its groups
    std::vector<PlannedLevel> order;  // this update's wanted levels in priority order
    std::uint64_t resident = 0;
    std::uint64_t frame = 0;
    std::uint64_t frame_uploaded = 0;
    plugin_msgs::ResidencyReport report;
    std::vector<plugin_msgs::StreamEvent> events;
    StreamerStats stats;
    engine::Subscription lod_subscription;
    std::optional<plugin_msgs::LodRule> bus_rule;  // the latest LodSettings' rule on the bus, once there is one
    float group_cell_scale = 1.0f;
    // What an update looks at (chunk_streamer.h, "the work of an update"): the nodes the cut's walks
    // visit, and those left with any state by the last update. Every other node is idle: not in or
    // near the cut, nothing requested, loaded or uploaded, not on screen, not failed but for a wrong
    // manifest entry; the update would leave it so.
    std::vector<std::size_t> roots;                // nodes without a parent
    std::vector<std::size_t> live;                 // nodes with state after the last update (all before the first)
    std::vector<std::size_t> work;                 // this update's nodes: the walks' and the live ones
    std::uint64_t stamp = 0;                       // this update's mark in ChunkSlot::visited
    glm::vec3 eye{0.0f}, eye_ahead{0.0f};          // the camera now and as anticipated (plan)
    std::uint64_t permanent_failures[2] = {0, 0};  // wrong manifest entries: chunks, groups
    bool permanent_failures_reported = false;      // once, by the first update
    std::unique_ptr<StreamReader> reader;          // last: destroyed (and joined) first

    // stream_plan.cpp
    void plan(const StreamView& view);
    LevelRank rank(std::size_t chunk, int level) const;
    bool make_room(std::uint64_t bytes);  // evicts levels outside the target set only
    void enforce_memory_budget();         // evicts anything, worst first, down to the budget

    void link_groups();                       // parents and children of the quadtree, the roots
    void touch(std::size_t k);                // k joins this update's work, with its distances
    void keep_live();                         // after an update: the live nodes; the rest idle
    void retry_failed();                      // a failed node is tried again after the settings' frames
    void choose_cut(const StreamView& view);  // ChunkSlot::in_cut
    void decide_drawn();                      // ChunkSlot::drawn

    // stream_fade.cpp
    void advance_fades();  // ChunkSlot::fade, LevelSlot::fade; ResidencySink::show and fade
    float part_opacity(const ChunkSlot& slot, int level) const;  // LevelPart::opacity of a new part

    // chunk_streamer.cpp
    void layout_levels(ChunkSlot& slot) const;
    void apply_pending_settings();
    void report_construction_failures();
    void release_unwanted();
    void collect_reads();
    void upload_loaded();
    void request_reads();
    void publish_report(std::uint64_t frame_index);
    // Drops levels `level` down to 1 (finest first) of a chunk: cancels reads, discards decoded parts,
    // releases uploaded parts through the sink with an `evicted` event.
    void drop_levels(std::size_t chunk, int level, DropReason reason);
    void fail_chunk(std::size_t chunk, int level, const std::string& problem);
    void emit(plugin_msgs::StreamEvent event);
};

std::string_view to_string(DropReason reason);
// Throws engine::Error for a view update() cannot use: a camera position or velocity that is not finite,
// a focal length that is not positive, a cut scale below 1 (stream_settings.cpp).
void check_view(const StreamView& view);

}  // namespace splat_lod::world
