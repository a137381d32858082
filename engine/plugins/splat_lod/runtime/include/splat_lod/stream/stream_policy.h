#pragma once
// The stateless rules of chunk streaming (chunk_streamer.h), stated once so that the streamer,
// its tests and a UI compute the same numbers: how far away a chunk is, and from how far a finer level could be
// selected (world_manifest.h, docs/algorithms.md §3).
#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "splat_lod/core/world_manifest.h"
#include "splat_lod/gpu_storage.h"
#include "splat_lod/msgs/lod_rule.h"

namespace splat_lod::world {

// What an upload costs on the GPU is the GPU scene's to say (splat_lod/gpu_storage.h); the streamer
// counts with it.
using splat_lod::gpu_bytes;
using splat_lod::gpu_bytes_per_gaussian;
using splat_lod::GpuStorage;
using splat_lod::max_gaussians_within;
using splat_lod::page_layout;
using splat_lod::PageLayout;

// Euclidean distance from `point` to the box of the chunk's Gaussian means (0 inside it). Every
// Gaussian of the chunk is at least this far from the camera, which is what makes it a bound.
float nearest_distance(const ChunkEntry& chunk, const glm::vec3& point);

// The largest distance at which some Gaussian of stream level `level` (1..3) of a chunk could be
// selected, from the manifest's per-level bounds (world_manifest.h):
//   f · max(2·extent_max / S_T, 2·extent_per_min_coverage_max / S_rel_min),
// +∞ when extent_per_min_coverage_max < 0 (a Gaussian of the level has no coverage_min, so the
// "not too small" test never rejects it), 0 for an empty level. Level 4 is not decided by distance
// (every chunk keeps its coarse prefix), so asking for it is a programming error.
// Only the rule's "not too small" thresholds S_T and S_rel_min enter: smooth transitions fade a
// Gaussian out before that switch, never past it (splat_lod/core/lod_selection.h).
double level_load_distance(const ChunkEntry& chunk, int level, double focal_length_px,
                           const plugin_msgs::LodRule& rule);

// How many pixels one pooling cell of a chunk group spans for the cut (chunk_streamer.h, "the cut") at
// `distance`, the group's nearest distance: cell_m · f / distance, times √min(1, a / sin(grazing_deg))
// when grazing_deg > 0. a is the projected area of the group's box per unit of its ground area, seen
// from `camera` toward the box's centre: a = |d_y| + e_y · (|d_x| / e_x + |d_z| / e_z), with d that unit
// direction and e the box of the Gaussians' means widened by one cell (a pooled Gaussian is up to a cell
// across); a flat box seen at elevation θ has a ≈ sin θ. So a group seen from above grazing_deg counts
// by its cell's edge, as without the factor; one seen at a grazing angle, whose Gaussians share few
// pixel rows (as a Gaussian's coverage, docs/algorithms.md §2, the shorter chord, shrinks when it is seen
// edge-on), counts for fewer pixels and stands in from nearer. Never more than the edge's value.
double group_cell_pixels(const ChunkEntry& group, const glm::vec3& camera, float distance, double focal_length_px,
                         float grazing_deg);

// The splat budget and the cut (chunk_streamer.h): the renderer meets a per-frame splat budget on the
// GPU by raising its size threshold, which moves the per-Gaussian cut inside chunks but cannot make a
// chunk group coarser (group Gaussians are drawn whole). Fed with the renderer's latest statistics
// (a few frames late), this returns the streamer's next scale of group_cell_px: when the
// selection wanted `unbudgeted` > `budget` Gaussians it grows toward scale·√(unbudgeted / budget) (a
// group's count falls with the square of its switch), at most 2^(1/4) per call; below 70 % of the
// budget it shrinks by 2^(1/8) per call, never below 1; in between it stays. 1 without a budget.
float next_group_cell_scale(float scale, std::uint64_t unbudgeted, std::uint64_t budget);

// An empty string when the entry can be streamed, otherwise what is wrong with it (prefix counts
// not ordered coarse to fine, no bytes per record, counts beyond the file size). The streamer marks
// such a chunk failed without reading it.
std::string check_chunk_entry(const ChunkEntry& chunk);

}  // namespace splat_lod::world
