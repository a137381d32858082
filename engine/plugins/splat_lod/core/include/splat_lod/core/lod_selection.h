#pragma once
// Pixel coverage (multi-scale paper §4.1, docs/algorithms.md §2) and the per-frame selection rule (paper
// Eq. 6 / Algorithm 2, docs/algorithms.md §3), stated once on the CPU. The GPU's splat_project pass
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
};

// S = 2·min(sqrt(L / Σ⁻¹ₓₓ), sqrt(L / Σ⁻¹ᵧᵧ)), L = 2·ln(255·opacity), from the UNdilated 2D
// covariance (xx, xy, yy). 0 when opacity ≤ 1/255 or the covariance is degenerate.
double pixel_coverage(double cov_xx, double cov_xy, double cov_yy, double opacity);

// Whether a Gaussian of `level` with coverage S this frame is drawn; coverage bounds of −1 are
// unset (no filtering on that side). Modes: baseline = finest level only, no filter;
// filter_small = finest level only, rule applied; insert_large = every level, no filter; full.
bool lod_selected(const LodRule& rule, int level, double coverage, double coverage_min, double coverage_max);

}  // namespace splat_lod
