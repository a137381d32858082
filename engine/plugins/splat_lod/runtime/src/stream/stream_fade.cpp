// Fades of what the chunk streamer draws (chunk_streamer.h, "fades"): after decide_drawn, each node's
// opacity moves one step of 1 / fade_frames toward 1 (drawn) or 0 (not drawn), and each uploaded level
// of a node on screen fades in by itself; the sink hears of every change.
#include <algorithm>
#include <vector>

#include "stream/stream_state.h"

namespace splat_lod::world {

namespace {

bool fading_out(const ChunkSlot& slot) {
    return !slot.drawn && slot.fade > 0.0f;
}

// The largest sum of fades of nodes fading out on any path down from k's children (k excluded).
float fading_below(const std::vector<ChunkSlot>& chunks, std::size_t k) {
    float most = 0.0f;
    for (const std::size_t c : chunks[k].children)
        most = std::max(most, (fading_out(chunks[c]) ? chunks[c].fade : 0.0f) + fading_below(chunks, c));
    return most;
}

// The opacity node k (not drawn) must keep so that, with what replaces it, the ground it covers sums
// to 1: 1 − the fade of its replacement (its nearest drawn ancestor, else the smallest of its nearest
// drawn descendants) − the fades of the other nodes fading out beyond it on the same paths.
// −1 when k does not hand over: nothing drawn replaces it, or a node fading out lies between them
// (that node hands over instead).
float handover_opacity(const std::vector<ChunkSlot>& chunks, std::size_t k) {
    bool fading_between = false;
    for (std::size_t a = chunks[k].parent; a != ChunkSlot::kNoSlot; a = chunks[a].parent) {
        if (chunks[a].drawn)
            return fading_between ? -1.0f : std::max(0.0f, 1.0f - chunks[a].fade - fading_below(chunks, k));
        fading_between = fading_between || fading_out(chunks[a]);
    }
    float lowest = 2.0f;
    std::vector<std::size_t> todo(chunks[k].children.begin(), chunks[k].children.end());
    while (!todo.empty()) {
        const std::size_t c = todo.back();
        todo.pop_back();
        if (chunks[c].drawn) {
            lowest = std::min(lowest, chunks[c].fade);
            continue;
        }
        if (fading_out(chunks[c])) return -1.0f;
        todo.insert(todo.end(), chunks[c].children.begin(), chunks[c].children.end());
    }
    if (lowest > 1.0f) return -1.0f;
    float above = 0.0f;
    for (std::size_t a = chunks[k].parent; a != ChunkSlot::kNoSlot; a = chunks[a].parent)
        above += fading_out(chunks[a]) ? chunks[a].fade : 0.0f;
    return std::max(0.0f, 1.0f - lowest - above);
}

}  // namespace

void ChunkStreamer::State::advance_fades() {
    const float step = settings.fade_frames > 0 ? 1.0f / static_cast<float>(settings.fade_frames) : 1.0f;
    // Only this update's work can be drawn or on screen (stream_state.h).
    for (const std::size_t k : work) {
        ChunkSlot& slot = chunks[k];
        slot.fade = slot.drawn ? std::min(1.0f, slot.fade + step) : std::max(0.0f, slot.fade - step);
    }
    // A node that stops being drawn before it had faded in fully (the cut moved on mid-fade) would leave
    // part of its ground uncovered while its replacements fade in: the node next to them keeps what the
    // others on the same ground leave (handover_opacity), so the opacities there sum to 1 and nothing
    // coarser has to come back to fill the hole.
    std::vector<float> keep(work.size(), -1.0f);
    for (std::size_t i = 0; i < work.size(); ++i)
        if (!chunks[work[i]].drawn && chunks[work[i]].shown) keep[i] = handover_opacity(chunks, work[i]);
    for (std::size_t i = 0; i < work.size(); ++i)
        if (keep[i] >= 0.0f) chunks[work[i]].fade = std::max(chunks[work[i]].fade, keep[i]);
    for (const std::size_t k : work) {
        ChunkSlot& slot = chunks[k];
        const bool was_visible = slot.shown;
        const bool visible = slot.fade > 0.0f;
        if (visible != slot.shown) {
            slot.shown = visible;
            sink.show(slot.entry->id, visible);
        }
        for (int l = kLevels; l >= 1; --l) {
            LevelSlot& level = slot.level(l);
            if (!level.any_uploaded()) {
                level.fade = 0.0f;
                level.told = -1.0f;
                continue;
            }
            // A level that arrives while its node is on screen fades in by itself; one that was there
            // before the node came on screen is ready at once (the node's own fade-in covers it).
            level.fade = was_visible ? std::min(1.0f, level.fade + step) : 1.0f;
            const float opacity = slot.fade * level.fade;
            if (opacity == level.told) continue;
            level.told = opacity;
            sink.fade(slot.entry->id, l, opacity);
        }
    }
}

float ChunkStreamer::State::part_opacity(const ChunkSlot& slot, int level) const {
    return std::max(slot.level(level).told, 0.0f);
}

}  // namespace splat_lod::world
