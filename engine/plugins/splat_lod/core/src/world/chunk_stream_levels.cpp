// Stream levels of a chunk's Gaussians (world/stream_levels.h).
#include "splat_lod/core/stream_levels.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "splat_lod/core/gaussian_extent.h"

namespace splat_lod::world {

double gaussian_reach(const SplatCloud& cloud, std::size_t i, const StreamLevelRule& rule, int coarsest_level) {
    const int level = cloud.lod_level.empty() ? 1 : cloud.lod_level[i];
    const float coverage_min = cloud.coverage_min.empty() ? -1.0f : cloud.coverage_min[i];
    if (level >= coarsest_level || !(coverage_min > 0.0f)) return std::numeric_limits<double>::infinity();
    const double extent = gaussian_extent(cloud.log_scales[i], cloud.opacity_logits[i]);
    const double threshold = std::min(static_cast<double>(rule.lod.size_threshold_px),
                                      static_cast<double>(rule.lod.rel_min) * static_cast<double>(coverage_min));
    return 2.0 * extent / threshold;
}

int stream_level(double reach, const StreamLevelRule& rule) {
    for (int k = 0; k < 3; ++k)
        if (reach >= static_cast<double>(rule.reach_min[static_cast<std::size_t>(k)])) return 4 - k;
    return 1;
}

std::vector<std::uint8_t> stream_levels(const SplatCloud& cloud, const StreamLevelRule& rule) {
    std::vector<std::uint8_t> levels(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i)
        levels[i] = static_cast<std::uint8_t>(stream_level(gaussian_reach(cloud, i, rule), rule));
    return levels;
}

std::vector<std::uint32_t> stream_order(const SplatCloud& cloud, const StreamLevelRule& rule) {
    const std::vector<std::uint8_t> levels = stream_levels(cloud, rule);
    std::vector<std::uint32_t> order(cloud.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return levels[a] > levels[b]; });
    return order;
}

std::string check_stream_level_rule(const StreamLevelRule& rule) {
    if (!(std::isfinite(rule.lod.size_threshold_px) && rule.lod.size_threshold_px > 0.0f))
        return "S_T must be positive and finite";
    if (!(std::isfinite(rule.lod.rel_min) && rule.lod.rel_min > 0.0f)) return "S_rel_min must be positive and finite";
    for (std::size_t k = 0; k < rule.reach_min.size(); ++k) {
        if (!(std::isfinite(rule.reach_min[k]) && rule.reach_min[k] > 0.0f))
            return "reaches must be positive and finite";
        if (k > 0 && !(rule.reach_min[k] < rule.reach_min[k - 1]))
            return "reaches must decrease from stream level 4 to 2";
    }
    return {};
}

}  // namespace splat_lod::world
