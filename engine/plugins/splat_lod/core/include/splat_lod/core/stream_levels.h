#pragma once
// Stream levels: how a chunk file is ordered so that every prefix is exactly what some view
// distance needs. The bake levels do not do this by themselves: in the multi-scale method level 1
// also holds the large Gaussians (ground, trunks) that pass the "not too small" test from any
// distance, so a file ordered by bake level would need its whole finest level even from far away.
//
// A Gaussian's reach is the largest depth, per pixel of focal length, at which it can pass the
// "not too small" half of the selection rule (docs/algorithms.md §3): coverage ≤ 2·e·f / z
// (world/gaussian_extent.h) and the test needs coverage ≥ min(S_T, S_rel_min·S_min), so
//   reach = 2·e / min(S_T, S_rel_min·S_min)   (metres per pixel; selectable only while z ≤ reach·f).
// It is +∞ for the coarsest bake level and for Gaussians without S_min (never "too small"), and 0
// for a Gaussian that is never visible (e = 0).
//
// Its stream level is 4 when reach ≥ reach_min[0], else 3 when reach ≥ reach_min[1], else 2 when
// reach ≥ reach_min[2], else 1. A chunk file holds stream level 4 first, then 3, 2, 1; within one,
// the bake's order (bake level, size class, Morton curve) is kept, so runs of 256 stay coherent for
// the renderer's cluster culling. Streaming "level l" always means stream level l; the renderer
// still selects by each Gaussian's own bake level (lod_level), which the file keeps.
#include <array>
#include <cstdint>
#include <vector>

#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/msgs/lod_rule.h"

namespace splat_lod::world {

struct StreamLevelRule {
    // The selection rule the reaches are computed with (its S_T and S_rel_min; the renderer's
    // defaults). Another rule at run time moves the load distances, not the order: the streamer bounds
    // each stream level with the manifest's per-level extent maxima and its own rule.
    plugin_msgs::LodRule lod;
    // Smallest reach of stream levels 4, 3 and 2 (metres per pixel, decreasing): a Gaussian is in
    // stream level 4 from reach_min[0] on, and so on. How the defaults were chosen, and how they split
    // the default world, is in docs/world_lod.md ("Stream levels").
    std::array<float, 3> reach_min{1.4f, 1.0f, 0.7f};
};

// reach of Gaussian i of `cloud` (see above); `coarsest_level` is the coarsest bake level (4).
double gaussian_reach(const SplatCloud& cloud, std::size_t i, const StreamLevelRule& rule, int coarsest_level = 4);
// 1..4 for a reach.
int stream_level(double reach, const StreamLevelRule& rule);
// The stream levels of every Gaussian of `cloud`.
std::vector<std::uint8_t> stream_levels(const SplatCloud& cloud, const StreamLevelRule& rule);
// The permutation that orders `cloud` stream level 4 first, stable within a stream level.
std::vector<std::uint32_t> stream_order(const SplatCloud& cloud, const StreamLevelRule& rule);
// An empty string when the rule can be used, otherwise what is wrong (non-finite or non-positive
// thresholds, reaches not positive and strictly decreasing).
std::string check_stream_level_rule(const StreamLevelRule& rule);

}  // namespace splat_lod::world
