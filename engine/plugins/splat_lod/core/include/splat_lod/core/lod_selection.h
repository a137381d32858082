#pragma once
// Pixel coverage (Yan et al. §4.1, docs/algorithms.md §2) and the per-frame selection rule (Yan et
// al. Eq. 6 / Algorithm 2, docs/algorithms.md §3), stated once on the CPU. The GPU's splat_project pass
// implements the same rule; tests compare the two Gaussian for Gaussian.
#include "splat_lod/msgs/lod_rule.h"

namespace splat_lod {

// The rule's parameters and defaults are defined once, in the messages (splat_lod/msgs/lod_rule.h).
using plugin_msgs::LodRule;

// The bake levels a rule is evaluated over: level 1 is the finest (the trained scene); the coarsest
// level present in the scene is exempt from "not too small".
inline constexpr int kFinestLevel = 1;
inline constexpr int kDefaultCoarsestLevel = 4;

// S = 2·min(sqrt(L / Σ⁻¹ₓₓ), sqrt(L / Σ⁻¹ᵧᵧ)), L = 2·ln(255·opacity), from the UNdilated 2D
// covariance (xx, xy, yy). 0 when opacity ≤ 1/255 or the covariance is degenerate.
double pixel_coverage(double cov_xx, double cov_xy, double cov_yy, double opacity);

// Whether a Gaussian of `level` with coverage S this frame is drawn; coverage bounds of −1 are
// unset (no filtering on that side). What the mode does comes from its traits (lod_rule.h): only the
// finest level unless all_levels, every candidate drawn unless coverage_rule.
bool lod_selected(const LodRule& rule, int level, double coverage, double coverage_min, double coverage_max,
                  int coarsest_level = kDefaultCoarsestLevel);

// The weight in [0, 1] by which a Gaussian's opacity is scaled this frame; 0 means not drawn. With a
// band b > 0 in mode full, each of the rule's two tests becomes a ramp linear in log2 coverage, b
// octaves wide, placed by rule.transition_placement (shifts s_small, s_large: transition_shifts):
//   not too large: x = log2(S / (S_max·S_rel_max)),             w_large = clamp(1 − (x + s_large)/b, 0, 1);
//   not too small: y = log2(max(S / S_T, S / (S_min·S_rel_min))), w_small = clamp((y + s_small)/b, 0, 1);
// the weight is w_large·w_small (the exemptions of the finest and coarsest level and of unset bounds
// give 1). Placed `inside` a Gaussian fades out over the b octaves before its "too small" switch and
// fades in over the b octaves past its "too large" switch: both ramps lie where the hard rule draws
// it, so nothing is drawn that the hard rule does not draw. Placed `before`, a coarse Gaussian fades
// in over the b octaves before its "too large" switch, so that w_small(t) and w_large(t) of one log
// distance sum to 1 (a hand-over at one coverage is continuous in opacity); `centred` puts both ramps
// half past their switch. The placement `auto` is resolved per asset by LodRule::for_asset (unresolved
// it weighs as `before`). Outside the band the weight equals the hard rule. With b = 0 or in a mode
// without transitions it is 1 where lod_selected holds and 0 elsewhere.
double lod_weight(const LodRule& rule, int level, double coverage, double coverage_min, double coverage_max,
                  int coarsest_level = kDefaultCoarsestLevel);

}  // namespace splat_lod
