// Fades of what the chunk streamer draws (chunk_streamer.h, "fades"): after decide_drawn, each node's
// opacity moves one step of 1 / fade_frames toward 1 (drawn) or 0 (not drawn), and each uploaded level
// of a node on screen fades in by itself; the sink hears of every change.
#include <algorithm>

#include "stream/stream_state.h"

namespace splat_lod::world {

void ChunkStreamer::State::advance_fades() {
    const float step = settings.fade_frames > 0 ? 1.0f / static_cast<float>(settings.fade_frames) : 1.0f;
    for (ChunkSlot& slot : chunks) {
        const bool was_visible = slot.shown;
        slot.fade = slot.drawn ? std::min(1.0f, slot.fade + step) : std::max(0.0f, slot.fade - step);
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
