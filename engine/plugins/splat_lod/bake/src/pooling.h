#pragma once
// Internal to the bake (docs/algorithms.md §4): steps 4–5, one pooled Gaussian per cell, enlarged towards S_T.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "cells.h"
#include "stage_clock.h"

namespace splat_lod::bake::detail {

// Step 4: the pooled Gaussian of `members` (indices into `source`), written at `out` of `target`
// (which has the same SH degree and extras): mean position, quaternions flipped to the first member's
// hemisphere then averaged and renormalised, mean log-scales, mean activated opacity (back to a
// logit clamped to [1e−4, 1 − 1e−4]), mean SH coefficients and extra attributes.
void pool(const SplatCloud& source, std::span<const std::uint32_t> members, SplatCloud& target, std::size_t out);

// Like pool(), but position, rotation and scales are those of the moment-matched Gaussian of the
// members weighted by opacity, Σ = Σ wᵢ(Σᵢ + (μᵢ − μ)(μᵢ − μ)ᵀ) / Σ wᵢ: it covers the region its
// members fill rather than their average size (PoolingRule::moments).
void pool_moments(const SplatCloud& source, std::span<const std::uint32_t> members, SplatCloud& target,
                  std::size_t out);

// Raises every scale of the Gaussian at `index` to at least `ratio` × its largest (0: unchanged), so
// that a coarse Gaussian is not a thin disc or needle whose coverage collapses when seen edge-on.
void thicken(SplatCloud& cloud, std::size_t index, double ratio);

// Step 5: S_avg = mean over members of each member's median coverage at `scale` over the
// cameras that see it; members seen by no camera are left out; 0 when none is seen.
double mean_median_coverage(const CoverageTable& table, std::span<const std::uint32_t> members, int scale);
// clamp(S_T / S_avg, 1, max); max when S_avg is 0.
double enlargement(double size_threshold, double mean_coverage, double max_enlargement);

// Steps 1–5 for one level: pools the Gaussians of finer levels that are small at its scale into
// one new Gaussian per cell, enlarged towards S_T, and appends them (and their coverage rows).
// Returns the cells' members; the level's Gaussians start at its `first`.
LevelMembers build_level(SplatCloud& cloud, CoverageTable& table, int level, const Normaliser& normaliser,
                         const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options,
                         LevelSummary& summary, const StageClock& clock);

}  // namespace splat_lod::bake::detail
