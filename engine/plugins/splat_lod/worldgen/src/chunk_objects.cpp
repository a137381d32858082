// A chunk's objects: trees, grass patches, rocks and picket fences (world/chunk_content.h). Each kind
// is placed on its own global grid of cells, one candidate per cell at a random spot inside it; the
// chunk whose square holds that spot builds the object, from the cell's own random stream.
#include "splat_lod/synth/synth_common.h"

#include <algorithm>
#include <cmath>

#include "chunk_content.h"
#include "splat_lod/synth/world_streams.h"

namespace splat_lod::world {
namespace {

// Placement cells (metres) and the synth builders' detail at density 1. The details are far below
// the garden's 1: a square kilometre holds thousands of trees, and the leaves keep their real size
// (1–4 cm) at any detail, so sparse crowns of tiny leaves are exactly the content that aliases.
constexpr float kTreeCell = 7.0f;
constexpr float kGrassCell = 6.0f;
constexpr float kRockCell = 13.0f;
constexpr float kTreeDetail = 0.017f;
constexpr float kGrassDetail = 0.015f;
constexpr float kRockDetail = 0.07f;
constexpr float kFenceDetail = 0.3f;
constexpr float kGrassBladesPerSquareMetre = 1200.0f;  // append_grass's "hides the ground" density

// Calls visit(rng, spot) for each cell of size `cell` whose random spot lies in the square.
template <typename Visit>
void for_each_spot(const ChunkSquare& square, float cell, std::uint64_t seed, StreamKind kind, const Visit& visit) {
    const auto i0 = static_cast<std::int64_t>(std::floor(square.lo.x / cell));
    const auto i1 = static_cast<std::int64_t>(std::floor(square.hi.x / cell));
    const auto j0 = static_cast<std::int64_t>(std::floor(square.lo.y / cell));
    const auto j1 = static_cast<std::int64_t>(std::floor(square.hi.y / cell));
    for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t i = i0; i <= i1; ++i) {
            synth::Rng rng(seed, stream_id(kind, i, j));
            const float u = rng.uniform();
            const float v = rng.uniform();
            const glm::vec2 spot((static_cast<float>(i) + u) * cell, (static_cast<float>(j) + v) * cell);
            if (square.contains(spot)) visit(rng, spot);
        }
}

glm::vec3 stored_rgb(const SplatCloud& cloud, std::size_t i) {
    return cloud.sh_dc[i] * kShC0 + glm::vec3(0.5f);
}

// A few larger, darker Gaussians inside the crown among the leaves, so that a sparse crown reads
// as foliage with depth (shaded interior) rather than a cloud of specks.
void append_crown_filler(SplatCloud& cloud, const synth::IndexRange& leaves, synth::Rng& rng) {
    if (leaves.size() < 4) return;
    glm::vec3 centre(0.0f);
    for (std::size_t i = leaves.begin; i < leaves.end; ++i) centre += cloud.positions[i];
    centre /= static_cast<float>(leaves.size());
    const std::size_t count = 6 + leaves.size() / 6;
    for (std::size_t k = 0; k < count; ++k) {
        const std::size_t leaf =
            leaves.begin + static_cast<std::size_t>(rng.uniform_int(0, static_cast<int>(leaves.size()) - 1));
        synth::GaussianDraft d;
        d.position = centre + (cloud.positions[leaf] - centre) * rng.uniform(0.45f, 0.85f);
        d.axis_x = synth::random_unit_vector(rng);
        d.axis_y = synth::random_perpendicular(d.axis_x, rng);
        const float size = rng.uniform(0.12f, 0.25f);
        d.scale = glm::vec3(size, 0.8f * size, 0.4f * size);
        d.rgb = stored_rgb(cloud, leaf) * 0.55f;
        d.opacity_logit = rng.uniform(1.0f, 2.5f);
        synth::append_gaussian(cloud, d);
    }
}

// Shifts the Gaussians [begin, end) built on the plane y = 0 onto the terrain under each of them.
void drape(SplatCloud& cloud, std::size_t begin, const WorldTerrain& terrain) {
    for (std::size_t i = begin; i < cloud.size(); ++i)
        cloud.positions[i].y += terrain.height(cloud.positions[i].x, cloud.positions[i].z);
}

}  // namespace

void append_chunk_trees(SplatCloud& cloud, const ContentContext& c, const ChunkSquare& square, ContentCounts& counts) {
    const Thinning thin = thinning(kTreeDetail * c.density);
    const WorldTerrain& t = *c.terrain;
    for_each_spot(square, kTreeCell, c.seed, StreamKind::tree, [&](synth::Rng& rng, const glm::vec2& p) {
        // Forests are dense; a few lone trees stand in the meadows.
        const float probability = (0.85f * t.forest(p.x, p.y) + 0.025f) * thin.keep;
        if (!rng.chance(probability)) return;
        if (t.river_distance(p.x, p.y) < WorldTerrain::kRiverHalfWidth + 2.5f ||
            t.path_distance(p.x, p.y) < WorldTerrain::kPathHalfWidth + 2.0f || c.layout->blocked(p, 2.5f))
            return;
        const float ground = t.height(p.x, p.y);
        synth::TreeStyle style;
        style.detail = thin.detail;
        // Conifers take over on the higher ground.
        style.kind = rng.chance(std::clamp(0.3f + ground / 20.0f, 0.1f, 0.8f)) ? synth::TreeKind::conifer
                                                                               : synth::TreeKind::broadleaf;
        style.leaf_tint.x = rng.uniform(0.95f, 1.12f);
        style.leaf_tint.z = rng.uniform(0.85f, 1.0f);
        const float height = rng.uniform(4.5f, 9.0f);
        const std::size_t before = cloud.size();
        const synth::TreeSplats tree =
            synth::append_tree(cloud, glm::vec3(p.x, ground - 0.05f, p.y), height, rng, style);
        append_crown_filler(cloud, tree.leaves, rng);
        ++counts.trees;
        counts.tree_gaussians += cloud.size() - before;
    });
}

void append_chunk_grass(SplatCloud& cloud, const ContentContext& c, const ChunkSquare& square) {
    const Thinning thin = thinning(kGrassDetail * c.density);
    const WorldTerrain& t = *c.terrain;
    for_each_spot(square, kGrassCell, c.seed, StreamKind::grass, [&](synth::Rng& rng, const glm::vec2& p) {
        const float probability = (0.25f * (1.0f - t.forest(p.x, p.y)) + 0.04f) * thin.keep;
        if (!rng.chance(probability)) return;
        const float radius = rng.uniform(0.9f, 2.3f);
        if (t.river_distance(p.x, p.y) < WorldTerrain::kRiverHalfWidth + 1.0f + radius ||
            t.path_distance(p.x, p.y) < WorldTerrain::kPathHalfWidth + radius || c.layout->blocked(p, radius))
            return;
        const std::size_t begin = cloud.size();
        synth::append_grass(cloud, glm::vec3(p.x, 0.0f, p.y), radius, kGrassBladesPerSquareMetre, rng, thin.detail);
        drape(cloud, begin, t);
    });
}

void append_chunk_rocks(SplatCloud& cloud, const ContentContext& c, const ChunkSquare& square) {
    const Thinning thin = thinning(kRockDetail * c.density);
    const WorldTerrain& t = *c.terrain;
    for_each_spot(square, kRockCell, c.seed, StreamKind::rock, [&](synth::Rng& rng, const glm::vec2& p) {
        // Boulders gather on the river banks.
        const float river = t.river_distance(p.x, p.y);
        const float bank =
            river > WorldTerrain::kRiverHalfWidth + 1.0f && river < WorldTerrain::kRiverHalfWidth + 10.0f ? 1.0f : 0.0f;
        if (!rng.chance((0.13f + 0.3f * bank) * thin.keep)) return;
        glm::vec3 half_extents;
        half_extents.x = rng.uniform(0.3f, 1.1f);
        half_extents.y = half_extents.x * rng.uniform(0.55f, 0.75f);
        half_extents.z = half_extents.x * rng.uniform(0.7f, 1.0f);
        if (river < WorldTerrain::kRiverHalfWidth + half_extents.x ||
            t.path_distance(p.x, p.y) < WorldTerrain::kPathHalfWidth + half_extents.x ||
            c.layout->blocked(p, half_extents.x + 0.5f))
            return;
        // Seated at the lowest ground under it, so that no side floats on a slope.
        float ground = t.height(p.x, p.y);
        for (const glm::vec2 offset : {glm::vec2(1, 0), glm::vec2(-1, 0), glm::vec2(0, 1), glm::vec2(0, -1)})
            ground = std::min(ground, t.height(p.x + offset.x * half_extents.x, p.y + offset.y * half_extents.z));
        synth::append_rock(cloud, glm::vec3(p.x, ground, p.y), half_extents, rng, thin.detail);
    });
}

void append_chunk_fences(SplatCloud& cloud, const ContentContext& c, const ChunkSquare& square) {
    const Thinning thin = thinning(kFenceDetail * c.density);
    for (const PicketFenceSpec& fence : c.layout->picket_fences) {
        const glm::vec3 middle = 0.5f * (fence.start + fence.end);
        if (!square.contains(glm::vec2(middle.x, middle.z))) continue;
        synth::Rng rng(c.seed, stream_id(StreamKind::picket_fence, fence.index, 0));
        synth::append_picket_fence(cloud, fence.start, fence.end, fence.height, rng, thin.detail);
    }
}

}  // namespace splat_lod::world
