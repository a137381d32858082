// The ground of a generated or imported world for its walkthrough (world_ground.h).
#include "sample_game/world_ground.h"

#include <algorithm>
#include <cmath>

namespace sample_game {
namespace {

using splat_lod::world::WorldTerrain;

// Where the walk starts on a generated world: the x whose walk has the most forest beside the path
// (10 and 20 m either side: what the walker sees), its canopy flight counting half, keeping clear of
// the river (no bridge: the camera would stand in the water), and the nearer the centre the better.
// Searched on a grid of F/256 between −0.25 and +0.15 F, F the terrain's feature scale (its size up
// to a kilometre): a larger world walks where the world of its middle does.
float choose_walk_start(const WorldTerrain& t, const WalkLengths& len) {
    const float size = t.size(), scale = t.feature_scale();
    const float stretch = len.walk + 1.6f * len.canopy;
    const float lowest = -0.25f * scale, highest = std::min(0.15f * scale, 0.5f * size - stretch - 0.05f * size);
    float best_x = lowest, best_score = -1e30f;
    for (float x = lowest; x <= highest; x += scale / 256.0f) {
        float score = 0.0f;
        for (int j = 0; j <= 16; ++j) {
            const float along = stretch * static_cast<float>(j) / 16.0f;
            const float xs = x + along, z = t.path_z(xs);
            if (t.river_distance(xs, z) < WorldTerrain::kRiverHalfWidth + 10.0f) score -= 100.0f;
            float beside = 0.0f;
            for (const float offset : {10.0f, 20.0f}) beside += t.forest(xs, z + offset) + t.forest(xs, z - offset);
            score += (along <= len.walk ? 1.0f : 0.5f) * beside;
        }
        score -= 12.0f * std::sqrt(x * x + t.path_z(x) * t.path_z(x)) / scale;  // distance of the start from the centre
        if (score > best_score) {
            best_score = score;
            best_x = x;
        }
    }
    return best_x;
}

}  // namespace

WorldGround::WorldGround(const WorldTerrain& terrain) : terrain_(terrain), size_(terrain.size()) {
    walk_start_ = choose_walk_start(terrain, walk_lengths(*this));
}

WorldGround WorldGround::of(const splat_lod::world::WorldManifest& m) {
    if (m.ground.empty()) return WorldGround(WorldTerrain(m.seed, m.size_m, m.feature_scale()));
    WorldGround ground;
    ground.grid_ = m.ground;
    ground.size_ = m.size_m;
    ground.scale_ = m.chunk_size_m / 64.0f;
    // The walk runs along x through the middle of the densest chunk (Gaussians per grid cell), centred on it.
    const auto density = [](const splat_lod::world::ChunkEntry& c) {
        return static_cast<double>(c.prefix_count[0]) / static_cast<double>(1ull << (2 * c.span));
    };
    const auto densest = std::max_element(m.chunks.begin(), m.chunks.end(),
                                          [&](const auto& a, const auto& b) { return density(a) < density(b); });
    if (densest != m.chunks.end()) {
        const float side = static_cast<float>(1 << densest->span);
        const glm::vec2 middle = (glm::vec2(densest->cell) + 0.5f * side) * m.chunk_size_m;
        const WalkLengths len = walk_lengths(ground);
        const float stretch = len.walk + 1.6f * len.canopy;
        ground.walk_z_ = middle.y;
        ground.walk_start_ = std::clamp(middle.x - 0.5f * stretch, -0.5f * m.size_m, 0.5f * m.size_m - stretch);
    }
    return ground;
}

float WorldGround::height(float x, float z) const {
    return terrain_ ? terrain_->height(x, z) : grid_.height(x, z, size_);
}

float WorldGround::path_z(float x) const {
    return terrain_ ? terrain_->path_z(x) : walk_z_;
}

glm::vec2 WorldGround::path_direction(float x) const {
    return terrain_ ? terrain_->path_direction(x) : glm::vec2(1.0f, 0.0f);
}

WalkLengths walk_lengths(const WorldGround& ground) {
    const float size = ground.size(), s = ground.scale();
    return {std::clamp(0.09f * size, 8.0f * s, 90.0f * s), std::clamp(0.06f * size, 6.0f * s, 60.0f * s)};
}

}  // namespace sample_game
