// Steps 4–5 of the bake: pooling and enlargement (pooling.h).
#include "pooling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/lod_selection.h"
#include "splat_lod/core/parallel_for.h"

namespace splat_lod::bake::detail {

using reference::detail::sigmoid;

void pool_moments(const SplatCloud& source, std::span<const std::uint32_t> members, SplatCloud& target,
                  std::size_t out) {
    pool(source, members, target, out);
    double weight_sum = 0.0;
    glm::dvec3 mean(0.0);
    for (const std::uint32_t m : members) {
        const double w = 1.0 / (1.0 + std::exp(-static_cast<double>(source.opacity_logits[m])));
        weight_sum += w;
        mean += w * glm::dvec3(source.positions[m]);
    }
    if (!(weight_sum > 0.0)) return;
    mean /= weight_sum;
    glm::dmat3 covariance(0.0);
    for (const std::uint32_t m : members) {
        const double w = 1.0 / (1.0 + std::exp(-static_cast<double>(source.opacity_logits[m])));
        const glm::dvec3 s = glm::exp(glm::dvec3(source.log_scales[m]));
        const glm::dmat3 rs = rotation_of(source.rotations[m]) * glm::dmat3(s.x, 0, 0, 0, s.y, 0, 0, 0, s.z);
        const glm::dvec3 d = glm::dvec3(source.positions[m]) - mean;
        covariance += w * (rs * glm::transpose(rs) + glm::outerProduct(d, d));
    }
    covariance /= weight_sum;
    glm::dvec3 values;
    glm::dmat3 vectors;
    symmetric_eigen(covariance, values, vectors);
    if (glm::determinant(vectors) < 0.0) vectors[2] = -vectors[2];
    const glm::dquat q = glm::normalize(glm::quat_cast(vectors));
    if (!std::isfinite(q.w + q.x + q.y + q.z)) return;  // keep pool()'s geometry
    target.positions[out] = glm::vec3(mean);
    target.rotations[out] = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
                             static_cast<float>(q.z)};
    for (int axis = 0; axis < 3; ++axis)
        target.log_scales[out][axis] = static_cast<float>(0.5 * std::log(std::max(values[axis], 1e-30)));
}

void pool(const SplatCloud& source, std::span<const std::uint32_t> members, SplatCloud& target, std::size_t out) {
    if (members.empty()) engine::fail("bake: pooling an empty cell");
    const double n = static_cast<double>(members.size());
    glm::dvec3 position(0.0), log_scale(0.0), dc(0.0);
    glm::dvec4 quaternion(0.0);
    double opacity = 0.0;
    const Rotation& first = source.rotations[members[0]];
    const glm::dvec4 reference_q(first.w, first.x, first.y, first.z);
    const std::size_t stride = source.sh_rest_stride();
    std::vector<double> rest(stride, 0.0);
    for (const std::uint32_t m : members) {
        position += glm::dvec3(source.positions[m]);
        log_scale += glm::dvec3(source.log_scales[m]);
        dc += glm::dvec3(source.sh_dc[m]);
        opacity += sigmoid(source.opacity_logits[m]);
        const Rotation& r = source.rotations[m];
        glm::dvec4 q(r.w, r.x, r.y, r.z);
        // q and −q are the same rotation: average on the first member's hemisphere.
        if (glm::dot(q, reference_q) < 0.0) q = -q;
        quaternion += q;
        for (std::size_t k = 0; k < stride; ++k) rest[k] += source.sh_rest[m * stride + k];
    }
    target.positions[out] = glm::vec3(position / n);
    target.log_scales[out] = glm::vec3(log_scale / n);
    target.sh_dc[out] = glm::vec3(dc / n);
    // Every flipped q has a non-negative dot with the first, so the sum has at least its length.
    const double length = glm::length(quaternion);
    const glm::dvec4 q = length > 0.0 ? quaternion / length : glm::dvec4(1.0, 0.0, 0.0, 0.0);
    target.rotations[out] = {static_cast<float>(q[0]), static_cast<float>(q[1]), static_cast<float>(q[2]),
                             static_cast<float>(q[3])};  // (w, x, y, z), the order of reference_q
    const double mean_opacity = std::clamp(opacity / n, 1e-4, 1.0 - 1e-4);
    target.opacity_logits[out] = static_cast<float>(std::log(mean_opacity / (1.0 - mean_opacity)));
    for (std::size_t k = 0; k < stride; ++k) target.sh_rest[out * stride + k] = static_cast<float>(rest[k] / n);
    // Attributes the engine keeps but does not interpret (e.g. Mip-Splatting's filter_3D): the mean.
    for (std::size_t e = 0; e < target.extras.size() && e < source.extras.size(); ++e) {
        double sum = 0.0;
        for (const std::uint32_t m : members) sum += source.extras[e].values[m];
        target.extras[e].values[out] = static_cast<float>(sum / n);
    }
}

void thicken(SplatCloud& cloud, std::size_t index, double ratio) {
    if (!(ratio > 0.0)) return;
    glm::vec3& s = cloud.log_scales[index];
    const float floor = std::max({s.x, s.y, s.z}) + static_cast<float>(std::log(ratio));
    s = glm::max(s, glm::vec3(floor));
}

double mean_median_coverage(const CoverageTable& table, std::span<const std::uint32_t> members, int scale) {
    double sum = 0.0;
    std::size_t counted = 0;
    std::vector<double> seen;
    for (const std::uint32_t m : members) {
        seen.clear();
        for (const float s : table.row(m))
            if (s >= 0.0f) seen.push_back(s);
        if (seen.empty()) continue;
        sum += percentile(seen, 50.0) / scale;
        ++counted;
    }
    return counted == 0 ? 0.0 : sum / static_cast<double>(counted);
}

double enlargement(double size_threshold, double mean_coverage, double max_enlargement) {
    if (!(mean_coverage > 0.0)) return max_enlargement;
    return std::clamp(size_threshold / mean_coverage, 1.0, max_enlargement);
}

// Steps 1–5 for one level: pools the Gaussians of finer levels that are small at its scale into
// one new Gaussian per grid cell, enlarged towards S_T, and appends them (and their coverage).
// Returns the cells' members; the level's Gaussians start at its `first`.
LevelMembers build_level(SplatCloud& cloud, CoverageTable& table, int level, const Normaliser& normaliser,
                         const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options,
                         LevelSummary& summary, const StageClock& clock) {
    const int scale = level_scale(level);
    summary.level = level;
    summary.scale = scale;
    LevelMembers cells = small_by_cell(cloud, table, level, normaliser, cameras, options, summary);
    const std::vector<std::uint32_t>& members = cells.members;
    const std::vector<std::size_t>& starts = cells.starts;
    const std::size_t groups = starts.size() - 1;
    summary.added = groups;
    cells.first = cloud.size();
    if (groups == 0) return cells;
    const std::size_t first_new = cloud.size();
    cloud.resize(first_new + groups);
    std::vector<double> factors(groups, 1.0);
    reference::detail::parallel_for(
        groups, reference::detail::resolve_thread_count(options.threads), [&](std::size_t g) {
            const std::span<const std::uint32_t> cell(members.data() + starts[g], starts[g + 1] - starts[g]);
            const std::size_t out = first_new + g;
            cloud.lod_level[out] = static_cast<std::uint8_t>(level);
            if (options.pooling == PoolingRule::moments) {
                pool_moments(cloud, cell, cloud, out);
                thicken(cloud, out, options.min_axis_ratio);
                return;
            }
            pool(cloud, cell, cloud, out);
            thicken(cloud, out, options.min_axis_ratio);
            const double s_avg = mean_median_coverage(table, cell, scale);
            factors[g] = enlargement(options.rule.size_threshold_px, s_avg, options.max_enlargement);
            cloud.log_scales[out] += glm::vec3(static_cast<float>(std::log(factors[g])));
        });
    double sum = 0.0;
    for (const double f : factors) {
        sum += f;
        if (f >= options.max_enlargement) ++summary.at_max_enlargement;
    }
    summary.mean_enlargement = sum / static_cast<double>(groups);
    clock.report(0.5);
    table.append(cloud, first_new, cameras, options.znear, options.threads);
    return cells;
}

}  // namespace splat_lod::bake::detail
