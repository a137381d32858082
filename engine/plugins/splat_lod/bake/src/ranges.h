#pragma once
// Internal to the bake (docs/algorithms.md §4): step 6, the coverage range in which each Gaussian is drawn.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "cells.h"

namespace splat_lod::bake::detail {

// Step 6: coverage_min/max of every Gaussian at its own level's scale from the table.
void set_coverage_ranges(SplatCloud& cloud, const CoverageTable& table, double low_percentile, double high_percentile);

// Caps coverage_max of every coarse Gaussian that has one at the coverage where its members stop
// being drawn, so that it is not selected in views its members serve: a member m is drawn while
// its coverage is at least D_m = max(S_T, S_rel_min · coverage_min_m) (S_T alone when unset); in
// bake camera j the coarse Gaussian is r_j times the median member's coverage; with r and D the
// medians over cameras and members, the cap is r · D / S_rel_max (selected when S ≤ r · D).
void cap_coverage_max(SplatCloud& cloud, const CoverageTable& table, const std::vector<LevelMembers>& levels,
                      const BakeOptions& options);
// The cap for one coarse Gaussian from its coverage per camera (≤ 0: not seen), its members' and their
// coverage_min (≤ 0: unset); −1 when no camera sees it together with a member.
double member_cap(std::span<const float> coarse, const std::vector<std::span<const float>>& members,
                  std::span<const float> member_min, const BakeOptions& options);

// Step 6 for every Gaussian, and with BakeOptions::member_ranges the cap of each coarse Gaussian's
// coverage_max at the coverage where its members stop being drawn.
void set_ranges(SplatCloud& cloud, const CoverageTable& table, const std::vector<LevelMembers>& levels,
                const BakeOptions& options);

}  // namespace splat_lod::bake::detail
