#pragma once
// Internal to the world generator: the fine (level-1) Gaussians of one chunk, before the bake.
// A chunk holds the ground and water Gaussians inside its square and every object whose anchor
// (a tree's foot, a grass patch's or rock's centre, a picket fence's middle) lies inside it, whole,
// so objects near an edge reach into the neighbour (the manifest's bounds say how far). Each object
// draws from the random stream of its placement cell (world_streams.h), so a chunk's content
// depends only on the seed, the world's size and density and the chunk's square.
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/synth/world_terrain.h"
#include "world_layout.h"

namespace splat_lod::synth {
class Rng;
}

namespace splat_lod::world {

struct ContentContext {
    std::uint64_t seed = 1;
    float density = 1.0f;
    const WorldTerrain* terrain = nullptr;
    const WorldLayout* layout = nullptr;
    std::uint64_t colour_seed = 0;  // ground colour noise, shared by all chunks so colours continue across edges
};

// What a chunk's content is made of (Gaussians, except the object counts).
struct ContentCounts {
    std::size_t ground = 0, water = 0, trees = 0, tree_gaussians = 0, grass = 0, rocks = 0, fences = 0;
    ContentCounts& operator+=(const ContentCounts& other);
};

// A synth builder's detail (clamped to what the builders accept) and, below that clamp, the
// fraction of objects kept instead, so that the Gaussian count keeps following the density.
struct Thinning {
    float detail = 1.0f;
    float keep = 1.0f;
};
Thinning thinning(float detail);

// The square [lo, hi) (x, z) of a chunk.
struct ChunkSquare {
    glm::vec2 lo{0.0f}, hi{0.0f};
    bool contains(const glm::vec2& p) const { return p.x >= lo.x && p.x < hi.x && p.y >= lo.y && p.y < hi.y; }
};

SplatCloud make_chunk_content(const ContentContext& context, const ChunkSquare& square, ContentCounts* counts);

// The parts (chunk_ground.cpp, chunk_objects.cpp), each appending to `cloud`.
void append_chunk_ground(SplatCloud& cloud, const ContentContext& context, const ChunkSquare& square, synth::Rng& rng);
void append_chunk_water(SplatCloud& cloud, const ContentContext& context, const ChunkSquare& square, synth::Rng& rng);
void append_chunk_trees(SplatCloud& cloud, const ContentContext& context, const ChunkSquare& square,
                        ContentCounts& counts);
void append_chunk_grass(SplatCloud& cloud, const ContentContext& context, const ChunkSquare& square);
void append_chunk_rocks(SplatCloud& cloud, const ContentContext& context, const ChunkSquare& square);
void append_chunk_fences(SplatCloud& cloud, const ContentContext& context, const ChunkSquare& square);

}  // namespace splat_lod::world
