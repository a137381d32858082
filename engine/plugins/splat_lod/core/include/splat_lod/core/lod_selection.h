#pragma once
// Pixel coverage (Yan et al. §4.1, docs/algorithms.md §2) and the per-frame selection rule (Yan et
// al. Eq. 6 / Algorithm 2, docs/algorithms.md §3), stated once on the CPU. The GPU's splat_project pass
// implements the same rule; tests compare the two Gaussian for Gaussian.
#include "splat_lod/msgs/lod_settings.h"

namespace splat_lod {

struct LodRule {
    plugin_msgs::LodMode mode = plugin_msgs::LodMode::full;
    double size_threshold_px = 2.0;  // S_T
    double rel_min = 0.5;            // S_rel_min
    double rel_max = 1.5;            // S_rel_max
    int finest_level = 1;
    int coarsest_level = 4;  // the coarsest level present in the scene
    // Octaves of coverage over which a Gaussian fades at each switch of the rule (0: hard switching);
    // see lod_weight. Applies in mode full only.
    double transition_band = plugin_msgs::LodSettings::kDefaultTransitionBand;
};

// S = 2·min(sqrt(L / Σ⁻¹ₓₓ), sqrt(L / Σ⁻¹ᵧᵧ)), L = 2·ln(255·opacity), from the UNdilated 2D
// covariance (xx, xy, yy). 0 when opacity ≤ 1/255 or the covariance is degenerate.
double pixel_coverage(double cov_xx, double cov_xy, double cov_yy, double opacity);

// Whether a Gaussian of `level` with coverage S this frame is drawn; coverage bounds of −1 are
// unset (no filtering on that side). Modes: baseline = finest level only, no filter;
// filter_small = finest level only, rule applied; insert_large = every level, no filter; full.
bool lod_selected(const LodRule& rule, int level, double coverage, double coverage_min, double coverage_max);

// The weight in [0, 1] by which a Gaussian's opacity is scaled this frame; 0 means not drawn. With a
// band b > 0 in mode full, each of the rule's two tests becomes a ramp linear in log2 coverage, b
// octaves wide, on the side of its switch where the hard rule draws the finer Gaussian:
//   not too large: x = log2(S / (S_max·S_rel_max)),             w_large = clamp(1 − x/b, 0, 1);
//   not too small: y = log2(max(S / S_T, S / (S_min·S_rel_min))), w_small = clamp(y/b, 0, 1);
// the weight is w_large·w_small (the exemptions of the finest and coarsest level and of unset bounds
// give 1). A Gaussian fades out over the b octaves before its "too small" switch, so none is drawn
// where the hard rule would not draw it, and a coarser one fades in over the b octaves before its
// "too large" switch, where the hard rule still draws its members: the band adds only coarse
// Gaussians, which are few. Outside the band the weight equals the hard rule; w_small(t) and
// w_large(t) sum to 1, so a Gaussian fading out at a coverage where its replacement fades in hands its
// opacity over continuously. With b = 0 or in the other modes it is 1 where lod_selected holds and 0
// elsewhere.
double lod_weight(const LodRule& rule, int level, double coverage, double coverage_min, double coverage_max);

}  // namespace splat_lod
