#pragma once
// The streamed chunks of a world counted by state, for the game's panel and the profile's records.
#include <array>
#include <cstdint>

namespace sample_game {

// How many chunks are in each state, a chunk's state being that of the least advanced level it
// needs (ChunkStatus: finest_needed_level .. 4), so the five counts add up to the chunk count.
struct ChunkCensus {
    std::uint32_t absent = 0, requested = 0, loaded = 0, partial = 0, resident = 0;
    std::array<std::uint32_t, 5> finest_resident{};  // [0]: not even level 4 resident; [l]: levels 4..l
    std::uint32_t failed = 0;
};

}  // namespace sample_game
