#pragma once
// The quadtree over a world's chunk grid: the group at depth d ≥ 1 and index g holds the chunks
// whose grid index i = cell + count/2 satisfies floor(i / 2^d) = g (squares of 2^d × 2^d chunks).
// The generator pools each group's Gaussians (splat_lod/worldgen/world_groups.h); the streamer's cut
// walks the same tree (splat_lod/stream/chunk_streamer.h). Only the indexing lives here.
#include <string>

#include <glm/glm.hpp>

#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {

// Depths of the quadtree over `count` × `count` chunks: the smallest D with 2^D ≥ count (0 for one
// chunk: no groups).
int group_depths(int chunks_per_side);

// The chunk grid's side (round(size / chunk)) and the index offset count/2 of the manifest's cells.
int chunks_per_side(const WorldManifest& manifest);

// The group index at `depth` ≥ 1 of a chunk at grid `cell` (cells run from −count/2).
glm::ivec2 group_of_chunk(const glm::ivec2& chunk_cell, int chunks_per_side, int depth);

// "group_2_+001_+003": depth 2, index (1, 3).
std::string group_id(int depth, const glm::ivec2& index);

}  // namespace splat_lod::world
