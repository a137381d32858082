// What the chunk streamer wants this frame and what it gives up first (chunk_streamer.h, steps 1
// and 4, and the eviction order of step 5).
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "stream_state.h"

namespace splat_lod::world {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// m(l) = D(l) / z: how many times closer than its load distance the chunk is (∞ inside the bounds).
double margin(double load_distance, double distance) {
    if (!(load_distance > 0.0)) return 0.0;
    if (!(distance > 0.0)) return kInfinity;
    return load_distance / distance;
}

}  // namespace

bool LevelRank::operator<(const LevelRank& o) const {
    return std::tie(tier, primary, distance, coarseness, chunk) <
           std::tie(o.tier, o.primary, o.distance, o.coarseness, o.chunk);
}

LevelRank ChunkStreamer::State::rank(std::size_t chunk, int level) const {
    const ChunkSlot& slot = chunks[chunk];
    LevelRank r;
    r.tier = level != kLevels ? 1 : slot.in_cut ? 0 : 2;
    r.distance = slot.distance;
    r.primary = level == kLevels ? r.distance : -slot.level(level).margin;
    r.coarseness = -level;
    r.chunk = chunk;
    return r;
}

void ChunkStreamer::State::plan(const StreamView& view) {
    const double keep_factor = settings.unload_distance_factor;
    order.clear();
    eye = view.camera_position;
    eye_ahead = eye + view.camera_velocity * static_cast<float>(settings.anticipation_updates);
    // This update's work: what the cut's walks visit, then the live nodes. The walks set the cut's
    // flags of the nodes they visit; every other node is out of the cut.
    ++stamp;
    work.clear();
    for (const std::size_t c : live) chunks[c].in_cut = chunks[c].near_cut = false;
    choose_cut(view);
    for (const std::size_t c : live) touch(c);
    for (const std::size_t c : work) {
        ChunkSlot& slot = chunks[c];
        // Prefix semantics: a level is needed when it or any finer level could be selected. Nothing
        // of a node outside the cut is needed, but what is drawn stays (chunk_streamer.h, "the cut").
        double finer = 0.0;
        for (int l = 1; l < kLevels; ++l) {
            const double load = slot.failure_permanent || !slot.in_cut
                                    ? 0.0
                                    : level_load_distance(*slot.entry, l, view.focal_length_px, settings.rule) *
                                          settings.load_distance_scale;
            finer = std::max(finer, margin(load, slot.distance));
            slot.level(l).margin = finer;
        }
        slot.level(kLevels).margin = slot.in_cut || slot.on_screen() ? kInfinity : 0.0;
        // Outside the cut and beyond its hysteresis band nothing is held: the band is the hysteresis.
        // Within the band level 4 is kept (not loaded) like a finer level within its unload distance.
        const bool may_hold = slot.in_cut || slot.on_screen() || slot.near_cut;
        slot.finest_needed = kLevels;
        for (int l = kLevels - 1; l >= 1; --l)
            if (slot.level(l).margin >= 1.0) slot.finest_needed = l;

        for (int l = kLevels; l >= 1; --l) {
            LevelSlot& s = slot.level(l);
            const bool needed = s.margin >= 1.0;
            const bool within_keep = s.margin * keep_factor >= 1.0 || (l == kLevels && slot.near_cut);
            s.frames_outside_keep = s.active() && !within_keep ? s.frames_outside_keep + 1 : 0;
            const bool held = s.active() && may_hold && s.frames_outside_keep <= settings.unload_delay_frames;
            s.wanted = (needed || held) && !slot.failure_permanent && !slot.blocked(l) &&
                       (l == kLevels || slot.level(l + 1).wanted);
            s.target = false;
            if (s.wanted) order.push_back({rank(c, l), c, l});
        }
    }
    std::sort(order.begin(), order.end(), [](const PlannedLevel& a, const PlannedLevel& b) { return a.rank < b.rank; });

    // Greedy within the memory budget; a level that does not fit is skipped (with its finer levels,
    // which rank after it), and smaller ones further down may still fit.
    std::uint64_t planned = 0;
    for (const PlannedLevel& p : order) {
        ChunkSlot& slot = chunks[p.chunk];
        LevelSlot& s = slot.level(p.level);
        if (p.level < kLevels && !slot.level(p.level + 1).target) continue;
        const std::uint64_t bytes = s.complete() ? s.resident_bytes : s.planned_bytes;
        if (bytes > settings.memory_budget_bytes - planned) continue;
        planned += bytes;
        s.target = true;
    }
}

namespace {

struct EvictionCandidate {
    bool found = false;
    bool target = false;
    LevelRank rank;
    std::size_t chunk = 0;
    int level = 0;
};

// The level to give up first: outside the target set before inside it, then the worst rank. Only
// a chunk's finest level holding GPU memory is a candidate (what stays must be a coarse prefix).
EvictionCandidate worst_candidate(const ChunkStreamer::State& state, bool allow_target) {
    EvictionCandidate worst;
    for (const std::size_t c : state.work) {  // only live nodes hold memory
        const ChunkSlot& slot = state.chunks[c];
        int finest = 0;
        for (int l = 1; l <= kLevels && finest == 0; ++l)
            if (slot.level(l).any_uploaded()) finest = l;
        if (finest == 0) continue;
        const bool target = slot.level(finest).target;
        if (target && !allow_target) continue;
        const LevelRank r = state.rank(c, finest);
        if (!worst.found || (worst.target && !target) || (worst.target == target && worst.rank < r))
            worst = {true, target, r, c, finest};
    }
    return worst;
}

}  // namespace

void ChunkStreamer::State::retry_failed() {
    const int retry = settings.retry_failed_after_frames;
    for (const std::size_t c : live) {  // a failed node stays live until retried
        ChunkSlot& slot = chunks[c];
        if (slot.failed && !slot.failure_permanent && retry > 0 &&
            frame >= slot.failed_frame + static_cast<std::uint64_t>(retry)) {
            slot.failed = false;
            slot.failed_level = 0;
        }
    }
}

void ChunkStreamer::State::keep_live() {
    live.clear();
    for (const std::size_t k : work) {
        ChunkSlot& slot = chunks[k];
        bool state =
            slot.in_cut || slot.near_cut || slot.on_screen() || slot.shown || (slot.failed && !slot.failure_permanent);
        for (const LevelSlot& s : slot.levels) state = state || s.active();
        if (state) {
            live.push_back(k);
            continue;
        }
        // Idle: what plan() gives a node out of the cut with nothing loaded, so that it may be skipped.
        slot.finest_needed = kLevels;
        for (LevelSlot& s : slot.levels) {
            s.margin = 0.0;
            s.wanted = s.target = false;
            s.frames_outside_keep = 0;
        }
    }
}

bool ChunkStreamer::State::make_room(std::uint64_t bytes) {
    while (resident + bytes > settings.memory_budget_bytes) {
        const EvictionCandidate victim = worst_candidate(*this, false);
        if (!victim.found) return false;
        drop_levels(victim.chunk, victim.level, DropReason::memory);
    }
    return true;
}

void ChunkStreamer::State::enforce_memory_budget() {
    while (resident > settings.memory_budget_bytes) {
        const EvictionCandidate victim = worst_candidate(*this, true);
        if (!victim.found) return;
        drop_levels(victim.chunk, victim.level, DropReason::memory);
    }
}

}  // namespace splat_lod::world
