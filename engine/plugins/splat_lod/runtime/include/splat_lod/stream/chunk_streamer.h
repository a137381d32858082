#pragma once
// Streams a chunked world (world_manifest.h) prefix by prefix, GL-free: a background
// reader decodes ranges of chunk files (ChunkSource), the main thread hands them to the GPU side
// (ResidencySink) within a per-frame byte budget, and GPU memory stays within a memory budget.
// Events and one residency report per frame go out as plugin_msgs on an engine::MessageBus.
//
// "Level" here is always a chunk's stream level (world/stream_levels.h): level 4 is what can be
// selected from any distance and stays resident, levels 3, 2, 1 are what is needed only within
// their load distances. The renderer selects by each Gaussian's bake level, independently.
//
// Per frame (update()):
//  1. plan: per chunk, the nearest distance z from the camera to its bounds and, per finer level
//     l = 1..3, its margin m(l) = D(l) / z with D(l) the manifest's load distance
//     (level_load_distance(), × load_distance_scale); a level is needed while some level at least as
//     fine has m ≥ 1 (a chunk is a coarse prefix: level l needs levels l+1..4). Level 4 is always
//     needed. Hysteresis: a loaded level stays wanted while m ≥ 1 / unload_distance_factor, and for
//     unload_delay_frames frames after that. The wanted levels, in priority order — every chunk's
//     level 4 first (nearest first), then finer levels by margin (largest first, then nearest, then
//     coarser first) — are taken greedily while their bytes fit the memory budget: the target set.
//  2. release: loaded levels no longer wanted are released ("evicted", no longer needed); levels
//     being loaded but outside the target set are cancelled.
//  3. collect finished reads; a read that failed, or returned the wrong number of Gaussians or
//     Gaussians of another level, marks the chunk failed (one `failed` event).
//  4. evict while resident bytes exceed the memory budget (only after the budget was lowered).
//  5. upload loaded parts in priority order while the frame's bytes stay within the upload budget
//     (strictly: the first part that does not fit ends the frame's uploads), evicting non-target
//     levels when the memory budget needs room. Eviction order: levels outside the target set before
//     target ones, then the reverse of the priority order — the finest level of the farthest chunk
//     (smallest margin) first, level 4 of any chunk only when no finer level is left to evict.
//  6. request reads for target levels (in priority order, coarse before fine within a chunk), at most
//     max_requests_in_flight parts requested or waiting for upload.
//  7. publish the ResidencyReport.
//
// Chunk groups and the cut (world_groups.h): when the manifest has groups, every chunk and group is a
// node of a quadtree (a chunk's parent is its depth-1 group, or the group of depth span + 1 for an
// import's chunk of several cells, ChunkEntry::span; a group's the group one depth up), and
// step 1 first chooses the cut, top-down from the roots: a group is drawn instead of everything below
// it when its pooling cell projects to at most group_cell_px pixels at the group's nearest distance
// (cell_m · f / z ≤ group_cell_px, the left side reduced where the group's box is seen at a grazing
// angle: stream_policy.h, group_cell_pixels; the walk is top-down and stops at the first node in, so
// exactly one node on every root-to-chunk path is in the cut) and it has not failed; a chunk is in the cut when no
// group above it is. Only nodes in the cut are needed (a group as its single level 4, a chunk as
// before). Hysteresis: a loaded node that would be in the cut if the camera were
// unload_distance_factor times nearer or farther (the cuts for group_cell_px × and ÷ that factor) is
// kept, not drawn; any other node outside the cut is released at once, unless on screen (drawn or
// fading out, below): with
// the band, the frame delay would only hold memory that the view does not use. Level 4 of nodes
// outside the cut ranks after every finer level (evicted first).
//   After the uploads (step 5b) the streamer decides what is drawn, through ResidencySink::show():
// a node of the cut is drawn when its level 4 is complete; until then the finest complete nodes above
// or below it stand in: a node outside the cut whose children each have a complete cover (complete
// themselves, or all their children covered) draws through to them, else it is drawn itself when
// complete, so a coarser node still resident (fading out, or held) does not come back once finer ones
// are in; a cut group that is not complete yet leaves its resident descendants drawn. Whatever is
// drawn is held resident.
// So a camera that moves never sees a hole or a node drawn twice over the same ground where memory
// allows, and a failed chunk shows its group where that is resident.
//   The splat budget: group Gaussians are drawn whole, so the renderer's raised threshold cannot thin
// them. While a budget binds, its controller (splat_budget.h, owned by whoever sets the budget) gives
// each update a scale of group_cell_px for the cut (StreamView::cut_scale), so that coarser groups
// replace more chunks; group_cell_scale() says which the last update used. group_cell_px = 0
// or a manifest without groups: every chunk is always in the cut (the behaviour without groups).
//
// Fades (smooth transitions): what is drawn does not switch at once. A node (chunk or group) that
// becomes drawn fades in over fade_frames updates (its opacity 1/n, 2/n, … 1 through
// ResidencySink::fade), and a node that stops being drawn fades out over as many, staying shown and
// resident until its opacity reaches 0. Since decide_drawn swaps a coarse node for the finer ones
// that replace it in one update (only once they are complete), the two cross-fade with opacities that
// sum to 1. When the cut moves on before a fade has ended (a fast camera), a node that stops being
// drawn part-way through its fade-in keeps what its replacements and the other nodes fading out over
// the same ground leave (at least 1 minus their opacities), so that ground still sums to 1. A finer
// stream level that arrives while its node is on screen fades in by itself over fade_frames updates
// (its opacity is the node's times its own); one that arrives while the node is not shown takes the
// node's. fade_frames = 0: every change at once.
//
// The work of an update: the cut's walks visit the nodes above the cut and the cut itself, and stop
// there; every other step looks at those and at the nodes the last update left with any state (in or
// near the cut, something requested, loaded or uploaded, on screen, failed). The rest of the world is
// idle and would stay so, so an update costs what the view holds, not what the world holds
// (StreamerStats::nodes_last_update). Only new settings, a wrong manifest entry (reported once), and a
// cut group that is still loading (whose stand-ins below it are searched) reach further.
//
// Anticipation: a fade takes fade_frames updates, so a cut that switched only when the camera got far
// enough would keep the finer nodes (and their cost) for that long after. With a camera_velocity v,
// the cut decides each node by the farther of its distance now and its distance from the camera
// n = anticipation_updates updates ahead (p + n · v): a node the camera moves away from leaves the cut
// n updates early, so that with n = fade_frames its fade-out ends about when it is due; a node the
// camera approaches is decided by its distance now, so refinement is never delayed. While the camera
// moves away, what is drawn is coarser than the switch asks by at most the factor (z + n · |v|) / z.
// Loads and the hysteresis band use the distance now.
//
// Oversized levels: a level is read and uploaded in parts of at most
// floor(upload_budget / bytes per Gaussian) Gaussians, so no frame ever uploads more than the
// budget; the constructor rejects a budget below one Gaussian.
//
// Failures: a missing, truncated or corrupt chunk (anything the source throws) is reported once as
// a `failed` event naming the chunk, the file and the problem, and logged as a warning. Levels of
// that chunk coarser than the failed one stay resident (they were read and checked); the failed
// level and finer ones are not requested again until retry_failed_after_frames frames have passed
// (0: never). A manifest entry that cannot be right (check_chunk_entry()) fails at construction.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/core/message_bus.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/msgs/stream_events.h"
#include "splat_lod/stream/stream_interfaces.h"
#include "splat_lod/stream/stream_policy.h"

namespace splat_lod::world {

struct StreamerSettings {
    std::uint64_t upload_budget_bytes_per_frame = 8ull << 20;  // GPU bytes handed to the sink per update
    std::uint64_t memory_budget_bytes = 512ull << 20;          // GPU bytes resident at the end of any update
    int max_requests_in_flight = 8;                            // parts queued, being read or waiting for upload
    int gpu_sh_degree = 3;  // the SH degree the GPU scene stores (sets the bytes per Gaussian)
    PageLayout gpu_pages;   // how the GPU scene stores an upload (whole pages; splat_lod/gpu_storage.h)
    // The selection rule the renderer draws with (its S_T and S_rel_min decide the load distances). With
    // a bus the streamer follows the splat pass's plugin_msgs::LodSettings on it instead (the latest one
    // when it is made, every later one from the next update on): this one is used only until one is
    // published, and set_settings() keeps the bus's.
    plugin_msgs::LodRule rule;
    // Multiplies the manifest's load distances. The bound 2·e·f / z holds on the view axis; off axis
    // the perspective Jacobian enlarges a Gaussian by up to about 1 / cos²θ (θ: angle from the axis,
    // ≈1.6 at the edge of a 75° field of view), so a game may load earlier with e.g. 1.5.
    float load_distance_scale = 1.0f;
    float unload_distance_factor = 1.25f;  // ≥ 1: a loaded level stays while z ≤ factor · load distance
    int unload_delay_frames = 30;          // ... and for this many further frames
    int retry_failed_after_frames = 0;     // a failed chunk is tried again after this many frames; 0: never
    bool background_thread = true;         // false: reads run inside update() (tests, tools); same behaviour
    // A chunk group replaces its chunks where its pooling cell projects to at most this many pixels
    // (output pixels); 0: groups are never used. Chosen on the default world (docs/world_lod.md, "The
    // numbers that chose it").
    float group_cell_px = 2.0f;
    // Below this elevation (degrees) a group's cell counts for fewer pixels, by the projected area of the
    // group's box (stream_policy.h, group_cell_pixels): a group seen at a grazing angle stands in from
    // nearer, so that a larger world's far field seen from the ground costs about what a smaller one's
    // does (docs/world_lod.md, "How the costs grow with the world"). 0: by the cell's edge alone.
    float group_grazing_deg = 30.0f;
    // Updates over which a node or a newly arrived level fades in or out (see "fades"); 0: at once.
    // 4: on the default world's walkthrough 8 let fades overlap in the flyout (2.74 Gaussians per
    // pixel against 2.47 with 4; docs/world_lod.md, "Fades").
    int fade_frames = 4;
    // Updates ahead that the cut anticipates a moving camera by (see "anticipation"); 0: not at all.
    // The default is the fade's length, so that a fade-out ends about when its switch is due.
    int anticipation_updates = 4;
};

// What update() needs from the camera. The focal length is in pixels of the output image (LOD
// selects by coverage at the output resolution, docs/algorithms.md §5).
struct StreamView {
    glm::vec3 camera_position{0.0f};
    float focal_length_px = 1000.0f;
    std::uint64_t frame_index = 0;
    // How far the camera moves per update (world units), as the game expects it to go on; zero (the
    // default) when it stands still, or after a cut or a teleport. The cut uses it to start a node's
    // fade-out early (see "anticipation").
    glm::vec3 camera_velocity{0.0f};
    // What group_cell_px is multiplied by for this update's cut (≥ 1): a binding splat budget's, from its
    // controller (splat_budget.h); 1 without one.
    float cut_scale = 1.0f;
};

enum class LevelState {
    absent,     // not loaded, not being loaded
    requested,  // reads queued or in progress, nothing decoded yet
    loaded,     // some parts decoded and waiting for upload, none uploaded
    partial,    // some parts uploaded, not all
    resident,   // every part uploaded (an empty level is always resident)
};

struct ChunkStatus {
    std::string id;
    float distance = 0.0f;                     // nearest distance at the last update
    int finest_needed_level = 4;               // 1..4 at the last update
    int finest_resident_level = 0;             // levels 4..this are all resident; 0 when level 4 is not
    std::array<LevelState, kLevels> levels{};  // [l − 1]
    std::uint64_t resident_bytes = 0;          // GPU bytes uploaded for this chunk
    bool failed = false;
    std::string failure;  // the message of the last failure
    int depth = 0;        // 0: a chunk; ≥ 1: a chunk group of that depth
    bool in_cut = true;   // chosen to be drawn at the last update (see "the cut")
    bool drawn = false;   // drawn after the last update
};

struct StreamerStats {
    std::uint64_t updates = 0;
    std::uint64_t uploaded_bytes_last_update = 0;
    std::uint64_t max_uploaded_bytes_per_update = 0;
    std::uint64_t uploaded_bytes_total = 0;
    std::uint64_t peak_resident_bytes = 0;  // measured after each upload and eviction
    std::uint64_t reads_requested = 0;
    std::uint64_t reads_discarded = 0;  // finished reads of levels cancelled meanwhile
    std::uint64_t levels_evicted_for_memory = 0;
    std::uint64_t levels_released_unneeded = 0;
    std::uint64_t failures = 0;
    // Nodes (chunks and groups) the last update looked at: those its cut visited and those with anything
    // loading, resident, on screen or failed ("the work of an update"); the rest of the world is skipped.
    std::uint64_t nodes_last_update = 0;
};

class ChunkStreamer {
public:
    // `folder` is the manifest's folder (chunk files are relative to it). The source and the sink must
    // outlive the streamer; `bus` may be null. Throws engine::Error on invalid settings.
    ChunkStreamer(WorldManifest manifest, std::filesystem::path folder, StreamerSettings settings, ChunkSource& source,
                  ResidencySink& sink, engine::MessageBus* bus = nullptr);
    // Stops the reader (queued reads dropped, a read in progress finishes) and joins its thread. Does
    // not call the sink: call release_all() first if the GPU side should be emptied.
    ~ChunkStreamer();
    ChunkStreamer(const ChunkStreamer&) = delete;
    ChunkStreamer& operator=(const ChunkStreamer&) = delete;

    // Once per frame on the main thread. Throws engine::Error on a non-finite camera position or a
    // focal length that is not positive.
    void update(const StreamView& view);
    // Blocks until the reader has nothing queued or in progress (tests: update, wait_idle, update...).
    void wait_idle();
    // Releases every uploaded level through the sink (finest first) and cancels every read.
    void release_all();

    // Validated like the constructor's; budgets and rules apply from the next update (a lowered
    // memory budget is enforced by eviction in that update).
    void set_settings(const StreamerSettings& settings);
    const StreamerSettings& settings() const;

    std::uint64_t resident_bytes() const;
    std::size_t chunk_count() const;  // the manifest's chunks
    std::size_t group_count() const;  // the manifest's groups
    float group_cell_scale() const;   // the last update's StreamView::cut_scale (≥ 1)
    // A chunk's index (0 … chunk_count − 1) or a group's (chunk_count + its index in the manifest).
    std::optional<std::size_t> find_chunk(std::string_view id) const;
    // index < chunk_count() + group_count(): chunks, then groups.
    ChunkStatus chunk_status(std::size_t index) const;
    // The report published by the last update (all zero before the first).
    const plugin_msgs::ResidencyReport& residency() const;
    // The events of the last update, in the order they were published.
    const std::vector<plugin_msgs::StreamEvent>& last_events() const;
    const StreamerStats& stats() const;

    struct State;  // defined in runtime/src/stream/stream_state.h

private:
    std::unique_ptr<State> state_;
};

// Throws engine::Error naming the first invalid setting.
void validate(const StreamerSettings& settings);

}  // namespace splat_lod::world
