#pragma once
// Chunk groups: the coarse Gaussians that stand for whole squares of chunks far from the camera.
//
// Why: a chunk baked alone pools the cells that its border cuts in two and distils its coarse
// levels from renders in which the neighbours are missing, so a far field drawn from per-chunk
// levels shows the chunk grid, and the per-chunk levels cannot get coarser than one chunk: from the
// overview the world is still drawn from millions of leaves (docs/world_lod.md has the numbers).
//
// What: a quadtree over the chunk grid. The group at depth d ≥ 1 and index g = (gx, gz) holds the
// chunks whose grid index i = cell + count/2 (0 … count − 1 per axis) satisfies floor(i / 2^d) = g,
// i.e. squares of 2^d × 2^d chunks; the root is the first depth at which one group holds every
// chunk. A chunk that covers 2^s × 2^s cells (ChunkEntry::span s, an import's sparse ground) belongs
// to the groups of depth > s only: no group is made that such a chunk would fill or overflow. Each group is one file of
// Gaussians pooled from the finest (level-1) Gaussians of all its members on ONE world-aligned grid of cubic cells of
// edge cell_m(d) = base_cell_m · 2^(d − 1) anchored at the world's corner: every cell is pooled from every member whose
// mean lies in it, wherever the chunk borders fall, and since 2^d chunks are a whole number of cells, no cell straddles
// a group border either. The streamer draws a group instead of its chunks when its cells project to at most a set
// number of pixels (chunk_streamer.h), so a group is what the view would see of its members at that distance, and the
// far field costs what the screen holds, not what the world holds.
//
// Pooling a cell (moment matching, weights wᵢ = αᵢ·Aᵢ with Aᵢ the Gaussian's mean axis-projected area
// √det of Σᵢ's three 2×2 projections, i.e. how much it covers):
//   μ = Σ wᵢ μᵢ / W,  Σ = Σ wᵢ (Σᵢ + (μᵢ − μ)(μᵢ − μ)ᵀ) / W,  SH = Σ wᵢ SHᵢ / W,
//   α = 1 − Π (1 − min(0.99, αᵢ·Aᵢ / A)), A the pooled Gaussian's own area (after the fill below),
// so the pooled Gaussian covers the region its members fill, with their mean colour, and is as opaque
// as the members would be if each covered its share of that region independently (one member gives
// back itself; many faint ones add up; overlapping opaque ones saturate at 0.99). Its spread axes are
// then widened by GroupOptions::fill so that the pooled Gaussians of a surface overlap instead of
// leaving seams at every cell border. A Gaussian whose
// largest standard deviation is at least the cell (large ground splats, trunks at depth 1) is kept
// as it is: merging it with the small ones in its cell would only smear it.
//
// Group Gaussians carry bake level 4 and no coverage range, so the renderer's selection draws every
// one of them whenever the group is drawn (the streamer decides which groups are drawn, per frame).
// Determinism: the output depends only on the members' files (cells in Morton order, members in
// file order), so sharded and unsharded bakes give the same bytes.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/core/chunk_quadtree.h"
#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {

struct GroupOptions {
    bool enabled = true;
    // The pooling cell at depth 1 (metres); depth d pools at base_cell_m · 2^(d − 1). With the
    // streamer's default switch (a cell at most 2 px) and a 312 px focal length (640 × 360, 60°),
    // depth 1 replaces its chunks from 156 m, depth 2 from 312 m, depth 3 from 624 m, depth 4 from
    // 1248 m. 0.5 m was measured too: its depth 1 holds more Gaussians than the ground it pools
    // (docs/world_lod.md).
    float base_cell_m = 1.0f;
    // The pooled Gaussian's spread axes (standard deviation above a tenth of the cell) are widened by
    // this factor, its opacity lowered to keep the covered area (the α·A sum): a moment-matched
    // Gaussian of a uniformly filled cell has σ ≈ 0.29 cell, so neighbours leave a gap between them
    // where a surface runs on (docs/world_lod.md has the measurement that chose the default).
    float fill = 1.5f;
};

// An empty string when the options can be used with chunks of `chunk_size_m`, otherwise what is
// wrong (a non-positive cell, or chunks that are not a whole number of depth-1 half-cells: 2 chunks
// must be a whole number of depth-1 cells).
std::string check_group_options(const GroupOptions& options, float chunk_size_m);

// The pooling cell of `depth` ≥ 1.
float group_cell_size(const GroupOptions& options, int depth);

// The pooled Gaussians of one group: the level-1 Gaussians of `members` pooled on the world-aligned
// grid of edge `cell_m` anchored at `origin` (see the top of this file). SH degree: the highest of
// the members'. Every output Gaussian has bake level 4 and coverage −1; output in Morton order of the
// cells. Gaussians that are not drawable (non-finite values, zero rotation, opacity ≤ 1/255) are
// left out. Empty when no member has a drawable level-1 Gaussian.
SplatCloud pool_group(std::span<const SplatCloud> members, const glm::vec3& origin, float cell_m, float fill = 1.0f);
// The same bytes from members read when needed: read_member(k) for k = 0 … count − 1 in order, twice
// over, so that only one member is in memory at a time (build_groups reads each from its file).
SplatCloud pool_group(std::size_t count, const std::function<SplatCloud(std::size_t)>& read_member,
                      const glm::vec3& origin, float cell_m, float fill = 1.0f);

struct GroupProgress {
    int depth = 0;
    std::size_t done = 0, total = 0;  // groups over all depths
};

// Builds every group of a world whose chunks (`chunks`, files relative to `folder`) are on disk:
// reads each member's file (checked against its entry), pools, writes
// `folder / generation / groups / <id>` with chunk_extension(codec) and returns the groups' manifest entries (files
// relative to `folder`), depth 1 first, each depth in index order. `threads` groups are pooled at
// once. Throws engine::Error naming the group and the file on any failure.
std::vector<ChunkEntry> build_groups(const std::filesystem::path& folder, const std::filesystem::path& generation,
                                     const std::vector<ChunkEntry>& chunks, float size_m, float chunk_size_m,
                                     const GroupOptions& options, const StreamLevelRule& rule, ChunkCodec codec,
                                     int threads, const std::function<void(const GroupProgress&)>& progress = {});

// The manifest's `group_generator` string for these options ("" when groups are off): a cached
// world's groups are rebuilt when it differs.
std::string group_generator_settings(const GroupOptions& options);

}  // namespace splat_lod::world
