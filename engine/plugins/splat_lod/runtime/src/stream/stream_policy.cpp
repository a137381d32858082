// The stateless streaming rules (stream_policy.h).
#include "splat_lod/stream/stream_policy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/glm.hpp>

#include "engine/core/error.h"

namespace splat_lod::world {

float nearest_distance(const ChunkEntry& chunk, const glm::vec3& point) {
    const glm::vec3 lo = glm::min(chunk.bounds_min, chunk.bounds_max);
    const glm::vec3 hi = glm::max(chunk.bounds_min, chunk.bounds_max);
    return glm::length(point - glm::clamp(point, lo, hi));
}

double level_load_distance(const ChunkEntry& chunk, int level, double focal_length_px,
                           const plugin_msgs::LodRule& rule) {
    if (level < 1 || level >= kLevels)
        engine::fail("splat_lod::world::level_load_distance(): level must be 1..3, got " + std::to_string(level));
    const ChunkLevel& bounds = chunk.levels[static_cast<std::size_t>(level - 1)];
    // Always needed: some Gaussian has no coverage_min, so only "too large" could hide it.
    if (bounds.extent_per_min_coverage_max < 0.0f) return std::numeric_limits<double>::infinity();
    const double by_size = 2.0 * bounds.extent_max * focal_length_px / rule.size_threshold_px;
    const double by_ratio = 2.0 * bounds.extent_per_min_coverage_max * focal_length_px / rule.rel_min;
    const double distance = std::max(by_size, by_ratio);
    return distance > 0.0 ? distance : 0.0;  // NaN and negative bounds: never needed by distance
}

double group_cell_pixels(const ChunkEntry& group, const glm::vec3& camera, float distance, double focal_length_px,
                         float grazing_deg) {
    if (!(distance > 0.0f)) return std::numeric_limits<double>::infinity();  // at or inside the box
    const double full = static_cast<double>(group.cell_m) * focal_length_px / static_cast<double>(distance);
    if (!(grazing_deg > 0.0f)) return full;
    const glm::dvec3 lo = glm::min(glm::dvec3(group.bounds_min), glm::dvec3(group.bounds_max));
    const glm::dvec3 hi = glm::max(glm::dvec3(group.bounds_min), glm::dvec3(group.bounds_max));
    const double cell = group.cell_m;
    // The box of the Gaussians' means, widened by one cell: a pooled Gaussian is up to a cell across.
    const glm::dvec3 extent = hi - lo + glm::dvec3(cell);
    glm::dvec3 toward = 0.5 * (lo + hi) - glm::dvec3(camera);
    const double length = glm::length(toward);
    if (!(length > 0.0) || !std::isfinite(length)) return full;
    toward /= length;
    // The box's projected area per unit of its ground area (its top face seen straight down: 1).
    const double area = std::abs(toward.y) + extent.y * (std::abs(toward.x) / extent.x + std::abs(toward.z) / extent.z);
    const double grazing_area = std::sin(static_cast<double>(grazing_deg) * (std::numbers::pi / 180.0));
    return full * std::sqrt(std::min(1.0, area / grazing_area));
}

std::string check_chunk_entry(const ChunkEntry& chunk) {
    const auto& counts = chunk.prefix_count;
    for (int l = 1; l < kLevels; ++l)
        if (counts[static_cast<std::size_t>(l)] > counts[static_cast<std::size_t>(l - 1)])
            return "manifest prefix counts are not ordered coarse to fine (Gaussians with level >= " +
                   std::to_string(l + 1) + ": " + std::to_string(counts[static_cast<std::size_t>(l)]) +
                   ", with level >= " + std::to_string(l) + ": " +
                   std::to_string(counts[static_cast<std::size_t>(l - 1)]) + ")";
    if (chunk.codec == ChunkCodec::compact) {
        // The block sizes are in the file's header, which the reader checks against file_bytes.
        if (chunk.file_bytes < chunk.header_bytes) return "manifest says fewer file bytes than header bytes";
    } else if (counts[0] > 0 && chunk.vertex_bytes == 0) {
        return "manifest gives 0 bytes per Gaussian record";
    }
    if (chunk.vertex_bytes > 0 &&
        counts[0] > (std::numeric_limits<std::uint64_t>::max() - chunk.header_bytes) / chunk.vertex_bytes)
        return "manifest record count overflows a 64-bit byte count";
    if (chunk.codec == ChunkCodec::ply && chunk.prefix_bytes(1) != chunk.file_bytes)
        return "manifest says " + std::to_string(chunk.file_bytes) + " file bytes but " + std::to_string(counts[0]) +
               " records of " + std::to_string(chunk.vertex_bytes) + " bytes after a " +
               std::to_string(chunk.header_bytes) + "-byte header make " + std::to_string(chunk.prefix_bytes(1));
    for (int axis = 0; axis < 3; ++axis)
        if (!std::isfinite(chunk.bounds_min[axis]) || !std::isfinite(chunk.bounds_max[axis]))
            return "manifest bounds are not finite";
    for (const ChunkLevel& level : chunk.levels)
        if (std::isnan(level.extent_max) || std::isnan(level.extent_per_min_coverage_max))
            return "manifest level bounds are NaN";
    return {};
}

float next_group_cell_scale(float scale, std::uint64_t unbudgeted, std::uint64_t budget) {
    if (budget == 0 || !std::isfinite(scale) || scale < 1.0f) return 1.0f;
    const double ratio = static_cast<double>(unbudgeted) / static_cast<double>(budget);
    if (ratio > 1.0) {
        const double wanted = static_cast<double>(scale) * std::sqrt(ratio);
        return static_cast<float>(std::min({wanted, static_cast<double>(scale) * std::exp2(0.25), 1024.0}));
    }
    if (ratio < 0.7) return std::max(1.0f, scale / static_cast<float>(std::exp2(0.125)));
    return scale;
}

}  // namespace splat_lod::world
