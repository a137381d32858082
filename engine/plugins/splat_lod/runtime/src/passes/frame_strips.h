#pragma once
// Strips of tile rows (SplatPassSettings::frame_memory_limit, docs/gpu_storage.md "Strips"): how much
// one strip may hold, and which strips a frame starts with. Plain arithmetic, no GL.
#include <cstdint>
#include <vector>

namespace splat_lod {

// The most splats and pairs one strip may hold: no limit by default.
struct StripRoom {
    std::uint32_t splats = ~0u;
    std::uint32_t pairs = ~0u;
    bool limited() const { return splats != ~0u || pairs != ~0u; }
};

// The room of a frame memory limit of `limit` bytes (0: none) for projected splats and pairs of
// `key_words`-word keys, split between the two buffers by what a frame needed of each (`splats` and
// `pairs`; half and half when it needed none), each getting a quarter to three quarters.
StripRoom strip_room(std::uint64_t limit, std::uint64_t splats, std::uint64_t pairs, std::uint32_t key_words);

// A strip a frame drew: tile rows [first_row, end_row) and what it held.
struct DrawnStrip {
    std::uint32_t first_row = 0, end_row = 0;
    std::uint32_t splats = 0, pairs = 0;
};

// The strips a frame of `rows` tile rows starts with, top to bottom, each meant to need at most
// kStripFill of the room: one without a limit; else the last frame's strips, neighbours merged while
// together they needed at most that and any that needed more cut into equal parts; with no last frame
// of this many rows, one strip. A strip that still needs more than its room is split while it is drawn.
inline constexpr double kStripFill = 0.8;
std::vector<DrawnStrip> plan_strips(const StripRoom& room, const std::vector<DrawnStrip>& last, std::uint32_t rows);

}  // namespace splat_lod
