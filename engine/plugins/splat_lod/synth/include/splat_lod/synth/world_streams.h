#pragma once
// The sample world's random streams: one for every object. Each placement cell of each
// kind of object (a tree cell, a grass cell, a chunk's ground) draws from its own synth::Rng stream,
// named by the kind and the cell's integer coordinates, so an object's randomness never depends on
// which chunk asks for it, in which order chunks are generated, or on how many threads run. The
// terrain (world_terrain.h) and the world generator (splat_lod_worldgen) draw from them.
#include <cstdint>

namespace splat_lod::world {

enum class StreamKind : std::uint8_t {
    terrain = 1,   // the terrain's noise seeds, phases and offsets
    layout,        // houses, fences and posts along the path
    ground,        // a chunk's ground Gaussians (cell = chunk)
    water,         // a chunk's water Gaussians (cell = chunk)
    tree,          // a tree placement cell
    grass,         // a grass patch placement cell
    rock,          // a rock placement cell
    picket_fence,  // the picket fence in front of a house (cell = house index)
};

// kind in the top 8 bits, then 28 bits per coordinate (two's complement): unique for |i|, |j| < 2^27.
// synth::Rng hashes the stream number, so neighbouring cells still get unrelated sequences.
inline std::uint64_t stream_id(StreamKind kind, std::int64_t i, std::int64_t j) {
    constexpr std::uint64_t mask = (std::uint64_t{1} << 28) - 1;
    return (static_cast<std::uint64_t>(kind) << 56) | ((static_cast<std::uint64_t>(i) & mask) << 28) |
           (static_cast<std::uint64_t>(j) & mask);
}

}  // namespace splat_lod::world
