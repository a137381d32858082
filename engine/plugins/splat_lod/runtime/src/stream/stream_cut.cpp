// The chunk streamer's LOD cut over the quadtree of chunk groups (chunk_streamer.h, "the cut"): which
// nodes the view wants drawn (step 1) and which are drawn now, given what is resident (step 5b).
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <tuple>

#include "splat_lod/core/chunk_quadtree.h"
#include "stream_state.h"

namespace splat_lod::world {
namespace {

bool level4_complete(const ChunkSlot& slot) {
    const LevelSlot& s = slot.level(kLevels);
    return !slot.failure_permanent && !slot.blocked(kLevels) && !s.parts.empty() && s.complete();
}

bool level4_any(const ChunkSlot& slot) {
    return !slot.failure_permanent && slot.level(kLevels).any_uploaded();
}

}  // namespace

void ChunkStreamer::State::link_groups() {
    const auto find_roots = [this] {
        for (std::size_t k = 0; k < chunks.size(); ++k)
            if (chunks[k].parent == ChunkSlot::kNoSlot) roots.push_back(k);
    };
    if (manifest.groups.empty()) return find_roots();
    const int count = chunks_per_side(manifest);
    std::map<std::tuple<int, int, int>, std::size_t> by_cell;  // (depth, x, z) → slot of a group
    for (std::size_t k = manifest.chunks.size(); k < chunks.size(); ++k)
        by_cell[{chunks[k].depth, chunks[k].entry->cell.x, chunks[k].entry->cell.y}] = k;
    for (std::size_t k = 0; k < chunks.size(); ++k) {
        ChunkSlot& slot = chunks[k];
        // A chunk hangs from the group of depth span + 1 (one of span 0 from depth 1), a group from the next.
        const glm::ivec2 up =
            slot.depth == 0 ? group_of_chunk(slot.entry->cell, count, slot.entry->span + 1) : slot.entry->cell / 2;
        // Groups of a non-negative index only: floor and truncation agree.
        const int parent_depth = slot.depth == 0 ? slot.entry->span + 1 : slot.depth + 1;
        const auto it = by_cell.find({parent_depth, up.x, up.y});
        if (it == by_cell.end()) continue;
        slot.parent = it->second;
        chunks[it->second].children.push_back(k);
    }
    find_roots();
}

void ChunkStreamer::State::touch(std::size_t k) {
    ChunkSlot& slot = chunks[k];
    if (slot.visited == stamp) return;
    slot.visited = stamp;
    work.push_back(k);
    slot.distance = nearest_distance(*slot.entry, eye);
    slot.cut_distance =
        eye_ahead != eye ? std::max(slot.distance, nearest_distance(*slot.entry, eye_ahead)) : slot.distance;
}

void ChunkStreamer::State::choose_cut(const StreamView& view) {
    const bool groups_on = settings.group_cell_px > 0.0f && !manifest.groups.empty();
    // The cut for a switch of `pixels_max`, top-down from the roots: the walk stops at a node in it,
    // so what lies below is not visited (and not in: the last update's flags are cleared in plan()).
    // `ahead`: decide by ChunkSlot::cut_distance ("anticipation"), else by the distance now.
    const auto cut = [&](double pixels_max, bool ahead, auto&& assign) {
        std::function<void(std::size_t)> mark = [&](std::size_t k) {
            touch(k);
            const ChunkSlot& slot = chunks[k];
            bool in = true;  // a chunk with no group above it in the cut
            if (slot.depth > 0) {
                const float z = ahead ? slot.cut_distance : slot.distance;
                const double pixels = group_cell_pixels(*slot.entry, view.camera_position, z, view.focal_length_px,
                                                        settings.group_grazing_deg);
                const bool coarse_enough = z > 0.0f && pixels <= pixels_max;
                in = groups_on && coarse_enough && !slot.failed && !slot.failure_permanent;
            }
            assign(k, in);
            if (!in)
                for (const std::size_t c : slot.children) mark(c);
        };
        for (const std::size_t k : roots) mark(k);
    };
    const double switch_px = settings.group_cell_px * double{group_cell_scale}, band = settings.unload_distance_factor;
    cut(switch_px, true, [&](std::size_t k, bool in) {
        chunks[k].in_cut = in;
        chunks[k].near_cut = false;
    });
    // The hysteresis band: what would be in the cut if the camera were `band` times nearer or
    // farther stays resident (not drawn) once loaded, so that small moves do not reload it.
    for (const double pixels_max : {switch_px * band, switch_px / band})
        cut(pixels_max, false,
            [&](std::size_t k, bool in) { chunks[k].near_cut = chunks[k].near_cut || (in && !chunks[k].in_cut); });
}

void ChunkStreamer::State::decide_drawn() {
    for (const std::size_t k : work) chunks[k].drawn = false;  // only live nodes were drawn
    // covered: k's part of the view can be drawn whole from complete nodes at or below k (k itself, or
    // every child covered). The cut's own nodes are the finest such cover when they are complete.
    std::function<bool(std::size_t)> covered = [&](std::size_t k) {
        const ChunkSlot& slot = chunks[k];
        if (level4_complete(slot)) return true;
        if (slot.children.empty()) return false;
        for (const std::size_t c : slot.children)
            if (!covered(c)) return false;
        return true;
    };
    // Below a cut node that is not complete: what is resident there stays drawn, coarsest first.
    std::function<void(std::size_t)> fallback = [&](std::size_t k) {
        ChunkSlot& slot = chunks[k];
        if (level4_any(slot)) {
            slot.drawn = true;
            return;
        }
        for (const std::size_t c : slot.children) fallback(c);
    };
    std::function<bool(std::size_t)> any_below = [&](std::size_t k) {
        for (const std::size_t c : chunks[k].children)
            if (level4_any(chunks[c]) || any_below(c)) return true;
        return false;
    };
    std::function<void(std::size_t)> draw = [&](std::size_t k) {
        ChunkSlot& slot = chunks[k];
        if (slot.in_cut) {
            if (level4_complete(slot) || (level4_any(slot) && !any_below(k)))
                slot.drawn = true;
            else
                for (const std::size_t c : slot.children) fallback(c);
            return;
        }
        // Above the cut: the finest complete nodes stand in for what is not in yet. A coarse node stays
        // only where some child's part has no complete cover: once a node's children are in, a coarser
        // one that is still resident (fading out, or held) does not come back.
        bool children_covered = !slot.children.empty();
        for (const std::size_t c : slot.children) children_covered = children_covered && covered(c);
        if (!children_covered && level4_complete(slot)) {
            slot.drawn = true;  // the coarse node stays until what replaces it is in
            return;
        }
        for (const std::size_t c : slot.children) draw(c);
    };
    for (const std::size_t k : roots) draw(k);
}

}  // namespace splat_lod::world
