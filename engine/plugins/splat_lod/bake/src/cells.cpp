// Steps 2–3 of the bake: normalisation and cells (cells.h).
#include "cells.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/core/error.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/lod_selection.h"
#include "splat_lod/core/parallel_for.h"

namespace splat_lod::bake::detail {

glm::dvec3 Normaliser::apply(const glm::dvec3& p) const {
    const glm::dvec3 x = (p - centre) / radius;
    const double norm = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    if (!std::isfinite(norm)) {
        // Beyond double range after the division: the direction still decides the face of the cube.
        const glm::dvec3 d = p - centre;
        const double m = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
        return m > 0.0 && std::isfinite(m) ? 2.0 * d / m : glm::dvec3(0.0);
    }
    if (norm <= 1.0) return x;
    return (2.0 - 1.0 / norm) * x / norm;
}

Normaliser make_normaliser(const std::vector<reference::ReferenceCamera>& cameras, const SplatCloud& cloud) {
    Normaliser n;
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest()), sum(0.0);
    for (const auto& camera : cameras) {
        lo = glm::min(lo, camera.position);
        hi = glm::max(hi, camera.position);
        sum += camera.position;
    }
    n.centre = cameras.empty() ? glm::dvec3(0.0) : sum / static_cast<double>(cameras.size());
    const glm::dvec3 span = cameras.empty() ? glm::dvec3(0.0) : hi - lo;
    n.radius = 0.5 * std::max({span.x, span.y, span.z});
    if (n.radius > 1e-9 && std::isfinite(n.radius)) return n;

    n.from_gaussians = true;
    n.radius = 0.0;
    if (!cloud.empty()) {
        double largest = 0.0;
        for (int axis = 0; axis < 3; ++axis) {
            std::vector<double> values(cloud.size());
            for (std::size_t i = 0; i < cloud.size(); ++i) values[i] = cloud.positions[i][axis];
            const double p1 = percentile(values, 1.0), p99 = percentile(values, 99.0);
            largest = std::max(largest, p99 - p1);
        }
        n.radius = 0.5 * largest;
    }
    if (!(n.radius > 1e-9) || !std::isfinite(n.radius)) n.radius = 1.0;
    return n;
}

std::uint64_t grid_cell(const glm::dvec3& normalised, int cells) {
    std::uint64_t key = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const double t = (normalised[axis] + 2.0) / 4.0 * cells;
        const auto index = static_cast<std::uint64_t>(std::clamp(std::floor(t), 0.0, static_cast<double>(cells - 1)));
        key = key * static_cast<std::uint64_t>(cells) + index;
    }
    return key;
}

std::uint64_t cell_key(const glm::dvec3& p, int level, int grid_cells, const Normaliser& normaliser,
                       const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options) {
    const glm::dvec3 x = normaliser.apply(p);
    const std::uint64_t grid_key = grid_cell(x, grid_cells);
    if (options.cells == CellRule::grid || cameras.empty()) return grid_key;
    // The grid cell's edge in world units near p: 4B/cells inside the unit cube, stretched by the
    // contraction (radial derivative 1/‖x‖∞²) outside it.
    const glm::dvec3 unscaled = (p - normaliser.centre) / normaliser.radius;
    const double norm = std::max({std::abs(unscaled.x), std::abs(unscaled.y), std::abs(unscaled.z), 1.0});
    const double grid_edge = 4.0 * normaliser.radius / grid_cells * norm * norm;
    double nearest = std::numeric_limits<double>::infinity();
    const reference::ReferenceCamera* camera = &cameras.front();
    for (const auto& c : cameras) {
        const double d = glm::length(p - c.position);
        if (d < nearest) {
            nearest = d;
            camera = &c;
        }
    }
    const double d = std::max(options.znear, nearest);
    const int b = static_cast<int>(std::floor(std::log2(d)));
    const double edge = 2.0 * double(options.rule.size_threshold_px) * std::ldexp(1.0, b) * level_scale(level) /
                        std::max(camera->fx, camera->fy);
    if (!(edge > grid_edge) || !std::isfinite(edge)) return grid_key & ~(1ULL << 63);
    // Distance cell: (b, floor(p / edge)) hashed into the 63 low bits, the top bit set.
    std::uint64_t hash = 1469598103934665603ULL ^ static_cast<std::uint64_t>(static_cast<std::int64_t>(b) + 1024);
    for (int axis = 0; axis < 3; ++axis) {
        const double cell = std::floor(p[axis] / edge);
        const auto index = static_cast<std::uint64_t>(static_cast<std::int64_t>(std::clamp(cell, -4e15, 4e15)));
        hash = (hash ^ index) * 1099511628211ULL;
        hash ^= hash >> 29;
    }
    return hash | (1ULL << 63);
}

// Steps 1–3 for one level: the Gaussians of finer levels that some camera sees smaller than S_T at
// the level's scale, by cell. Cell g's members are members[starts[g] .. starts[g + 1]).
LevelMembers small_by_cell(const SplatCloud& cloud, const CoverageTable& table, int level, const Normaliser& normaliser,
                           const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options,
                           LevelSummary& summary) {
    const int scale = level_scale(level);
    const int cells = (options.grid_cells + level - 1) / level;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;  // (cell, Gaussian)
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (cloud.lod_level[i] >= level) continue;
        double smallest = std::numeric_limits<double>::infinity();
        bool seen = false;
        for (const float s : table.row(i))
            if (s >= 0.0f) {
                seen = true;
                smallest = std::min(smallest, static_cast<double>(s) / scale);
            }
        if (!seen) continue;
        ++summary.candidates;
        if (smallest >= options.rule.size_threshold_px) continue;
        ++summary.small;
        keyed.emplace_back(cell_key(glm::dvec3(cloud.positions[i]), level, cells, normaliser, cameras, options),
                           static_cast<std::uint32_t>(i));
    }
    // Sorted by (cell, index): the cells, their members and the first member (the quaternion
    // hemisphere) do not depend on anything but the input.
    std::sort(keyed.begin(), keyed.end());
    LevelMembers out;
    for (std::size_t j = 0; j < keyed.size(); ++j)
        if (j == 0 || keyed[j].first != keyed[j - 1].first) out.starts.push_back(j);
    out.starts.push_back(keyed.size());
    out.members.resize(keyed.size());
    for (std::size_t j = 0; j < keyed.size(); ++j) out.members[j] = keyed[j].second;
    return out;
}

}  // namespace splat_lod::bake::detail
