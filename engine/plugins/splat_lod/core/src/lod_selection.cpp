#include "splat_lod/core/lod_selection.h"

#include <algorithm>
#include <cmath>

namespace splat_lod {

double pixel_coverage(double cov_xx, double cov_xy, double cov_yy, double opacity) {
    if (!(opacity > 1.0 / 255.0)) return 0.0;
    const double det = cov_xx * cov_yy - cov_xy * cov_xy;
    if (!(det > 0.0) || !(cov_xx > 0.0) || !(cov_yy > 0.0)) return 0.0;
    const double level_set = 2.0 * std::log(255.0 * opacity);
    // Σ⁻¹ₓₓ = yy / det and Σ⁻¹ᵧᵧ = xx / det: the chords through the centre where α falls to 1/255.
    return 2.0 * std::min(std::sqrt(level_set * det / cov_yy), std::sqrt(level_set * det / cov_xx));
}

bool lod_selected(const LodRule& rule, int level, double coverage, double coverage_min, double coverage_max,
                  int coarsest_level) {
    const plugin_msgs::LodModeTraits mode = plugin_msgs::traits(rule.mode);
    if (!mode.all_levels && level != kFinestLevel) return false;
    if (!mode.coverage_rule) return true;
    // Eq. 6: not too large for its level (unless finest) and not too small (unless large enough
    // on screen, or coarsest).
    const bool not_too_large =
        level == kFinestLevel || coverage_max < 0.0 || coverage / coverage_max <= double(rule.rel_max);
    const bool not_too_small = level == coarsest_level || coverage_min < 0.0 ||
                               coverage >= double(rule.size_threshold_px) ||
                               coverage / coverage_min >= double(rule.rel_min);
    return not_too_large && not_too_small;
}

double lod_weight(const LodRule& rule, int level, double coverage, double coverage_min, double coverage_max,
                  int coarsest_level) {
    const double band = rule.transition_band;
    const plugin_msgs::LodModeTraits mode = plugin_msgs::traits(rule.mode);
    if (!mode.transitions || !mode.coverage_rule || !(band > 0.0) || !(coverage > 0.0))
        return lod_selected(rule, level, coverage, coverage_min, coverage_max, coarsest_level) ? 1.0 : 0.0;
    // Each ramp moved past its switch (toward the coarser side) by its placement's shift.
    const plugin_msgs::TransitionShifts shift = plugin_msgs::transition_shifts(rule.transition_placement, float(band));
    double weight = 1.0;
    if (level != kFinestLevel && coverage_max >= 0.0) {
        const double x = std::log2(coverage / (coverage_max * double(rule.rel_max)));
        weight *= std::clamp(1.0 - (x + double(shift.large)) / band, 0.0, 1.0);
    }
    if (level != coarsest_level && coverage_min >= 0.0) {
        const double y = std::log2(
            std::max(coverage / double(rule.size_threshold_px), coverage / (coverage_min * double(rule.rel_min))));
        weight *= std::clamp((y + double(shift.small)) / band, 0.0, 1.0);
    }
    return weight;
}

}  // namespace splat_lod
