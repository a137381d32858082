// Step 6 of the bake: coverage ranges (ranges.h).
#include "ranges.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/core/error.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/lod_selection.h"
#include "splat_lod/core/parallel_for.h"

namespace splat_lod::bake::detail {

void set_coverage_ranges(SplatCloud& cloud, const CoverageTable& table, double low_percentile, double high_percentile) {
    if (table.gaussians() != cloud.size()) engine::fail("bake: coverage table and scene differ in size");
    std::vector<double> seen;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const int scale = level_scale(cloud.lod_level[i]);
        seen.clear();
        for (const float s : table.row(i))
            if (s >= 0.0f) seen.push_back(static_cast<double>(s) / scale);
        if (seen.empty()) {
            cloud.coverage_min[i] = cloud.coverage_max[i] = -1.0f;
            continue;
        }
        cloud.coverage_min[i] = static_cast<float>(percentile(seen, low_percentile));
        cloud.coverage_max[i] = static_cast<float>(percentile(seen, high_percentile));
    }
}

double member_cap(std::span<const float> coarse, const std::vector<std::span<const float>>& members,
                  std::span<const float> member_min, const BakeOptions& options) {
    std::vector<double> ratios, sizes;
    for (std::size_t j = 0; j < coarse.size(); ++j) {
        if (!(coarse[j] > 0.0f)) continue;
        sizes.clear();
        for (const auto& row : members)
            if (row[j] > 0.0f) sizes.push_back(row[j]);
        if (!sizes.empty()) ratios.push_back(coarse[j] / percentile(sizes, 50.0));
    }
    if (ratios.empty()) return -1.0;
    std::vector<double> drop;
    for (const float m : member_min)
        drop.push_back(
            std::max(double(options.rule.size_threshold_px), m > 0.0f ? double(options.rule.rel_min) * m : 0.0));
    return percentile(ratios, 50.0) * percentile(drop, 50.0) / double(options.rule.rel_max);
}

void cap_coverage_max(SplatCloud& cloud, const CoverageTable& table, const std::vector<LevelMembers>& levels,
                      const BakeOptions& options) {
    if (table.gaussians() != cloud.size()) engine::fail("bake: coverage table and scene differ in size");
    for (const LevelMembers& level : levels) {
        const std::size_t groups = level.starts.empty() ? 0 : level.starts.size() - 1;
        reference::detail::parallel_for(
            groups, reference::detail::resolve_thread_count(options.threads), [&](std::size_t g) {
                const std::size_t coarse = level.first + g;
                if (!(cloud.coverage_max[coarse] > 0.0f)) return;
                std::vector<std::span<const float>> rows;
                std::vector<float> minima;
                for (std::size_t k = level.starts[g]; k < level.starts[g + 1]; ++k) {
                    rows.push_back(table.row(level.members[k]));
                    minima.push_back(cloud.coverage_min[level.members[k]]);
                }
                const double cap = member_cap(table.row(coarse), rows, minima, options);
                if (cap > 0.0)
                    cloud.coverage_max[coarse] = std::min(cloud.coverage_max[coarse], static_cast<float>(cap));
            });
    }
}

// Step 6, and with BakeOptions::member_ranges the cap of each coarse Gaussian's coverage_max at
// the coverage where its members stop being drawn.
void set_ranges(SplatCloud& cloud, const CoverageTable& table, const std::vector<LevelMembers>& levels,
                const BakeOptions& options) {
    set_coverage_ranges(cloud, table, options.range_low_percentile, options.range_high_percentile);
    if (options.member_ranges) cap_coverage_max(cloud, table, levels, options);
}

}  // namespace splat_lod::bake::detail
