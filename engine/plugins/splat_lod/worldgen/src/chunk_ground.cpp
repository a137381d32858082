// A chunk's ground and water Gaussians, and the assembly of its content (world/chunk_content.h).
#include "splat_lod/synth/synth_common.h"

#include <algorithm>
#include <cmath>

#include "chunk_content.h"
#include "splat_lod/synth/world_streams.h"

namespace splat_lod::world {
namespace {

// Grid spacings at density 1 (they shrink with √density, so the counts follow the density). The
// ground is far coarser than the garden's (5 cm): a square kilometre must fit the Gaussian budget,
// and the fine detail that aliases is in the leaves, blades and pickets standing on it.
constexpr float kGroundSpacing = 0.6f;
constexpr float kWaterSpacing = 0.45f;

// The grid of `spacing` that tiles [lo, hi) exactly, so neighbouring chunks meet without a seam.
struct Grid {
    int nx = 1, nz = 1;
    float dx = 1.0f, dz = 1.0f;
};

Grid grid_for(const ChunkSquare& square, float spacing) {
    Grid g;
    g.nx = std::max(1, static_cast<int>(std::ceil((square.hi.x - square.lo.x) / spacing)));
    g.nz = std::max(1, static_cast<int>(std::ceil((square.hi.y - square.lo.y) / spacing)));
    g.dx = (square.hi.x - square.lo.x) / static_cast<float>(g.nx);
    g.dz = (square.hi.y - square.lo.y) / static_cast<float>(g.nz);
    return g;
}

// Ground colour by what lies there: meadow, forest floor, the path's dirt, the river's banks and
// bed; metre-scale patches from the shared noise, then per-Gaussian grain and the fixed sun.
glm::vec3 ground_colour(const ContentContext& c, const glm::vec2& p, const glm::vec3& normal, synth::Rng& rng) {
    const WorldTerrain& t = *c.terrain;
    const float patch = synth::value_noise(p.x / 7.0f, p.y / 7.0f, c.colour_seed);
    const float moss = synth::value_noise(p.x / 2.3f, p.y / 2.3f, c.colour_seed + 1);
    const glm::vec3 meadow = synth::mix_rgb({0.29f, 0.41f, 0.15f}, {0.40f, 0.50f, 0.19f}, patch);
    const glm::vec3 floor = synth::mix_rgb({0.27f, 0.22f, 0.14f}, {0.24f, 0.31f, 0.13f}, moss);
    glm::vec3 rgb = synth::mix_rgb(meadow, floor, glm::smoothstep(0.1f, 0.6f, t.forest(p.x, p.y)));
    const float path = 1.0f - glm::smoothstep(WorldTerrain::kPathHalfWidth - 0.3f, WorldTerrain::kPathHalfWidth + 0.6f,
                                              t.path_distance(p.x, p.y));
    rgb = synth::mix_rgb(rgb, glm::vec3(0.52f, 0.43f, 0.30f) * (0.9f + 0.2f * moss), path);
    const float river = t.river_distance(p.x, p.y);
    const float bank =
        1.0f - glm::smoothstep(WorldTerrain::kRiverHalfWidth + 1.5f, WorldTerrain::kRiverHalfWidth + 4.0f, river);
    rgb = synth::mix_rgb(rgb, {0.55f, 0.50f, 0.38f}, bank);
    if (river < WorldTerrain::kRiverHalfWidth) rgb = glm::vec3(0.30f, 0.27f, 0.20f);
    const float grain = rng.uniform(0.85f, 1.1f);
    return rgb * synth::sun_shade(normal, 0.6f) * grain;
}

}  // namespace

ContentCounts& ContentCounts::operator+=(const ContentCounts& o) {
    ground += o.ground;
    water += o.water;
    trees += o.trees;
    tree_gaussians += o.tree_gaussians;
    grass += o.grass;
    rocks += o.rocks;
    fences += o.fences;
    return *this;
}

Thinning thinning(float detail) {
    if (detail >= synth::kMinDetail) return {std::min(detail, synth::kMaxDetail), 1.0f};
    return {synth::kMinDetail, detail / synth::kMinDetail};
}

void append_chunk_ground(SplatCloud& cloud, const ContentContext& c, const ChunkSquare& square, synth::Rng& rng) {
    const Grid g = grid_for(square, kGroundSpacing / std::sqrt(c.density));
    for (int iz = 0; iz < g.nz; ++iz)
        for (int ix = 0; ix < g.nx; ++ix) {
            // Jitter below half a cell keeps every cell occupied; scales of 0.6–1.15 × the spacing
            // overlap the neighbours (append_ground's recipe, laid on the terrain's slope).
            const float jx = rng.uniform(-0.35f, 0.35f);
            const float jz = rng.uniform(-0.35f, 0.35f);
            const glm::vec2 p(square.lo.x + (static_cast<float>(ix) + 0.5f + jx) * g.dx,
                              square.lo.y + (static_cast<float>(iz) + 0.5f + jz) * g.dz);
            const glm::vec3 normal = c.terrain->normal(p.x, p.y);
            const glm::vec3 yaw = synth::random_perpendicular(glm::vec3(0.0f, 1.0f, 0.0f), rng);
            synth::GaussianDraft d;
            d.position = glm::vec3(p.x, c.terrain->height(p.x, p.y) - rng.uniform(0.0f, 0.01f), p.y);
            d.axis_x = yaw - normal * glm::dot(yaw, normal);  // tangent to the slope
            d.axis_x /= std::sqrt(glm::dot(d.axis_x, d.axis_x));
            d.axis_y = normal;
            const float spacing = std::max(g.dx, g.dz);
            const float long_scale = spacing * rng.uniform(0.75f, 1.15f);
            const float short_scale = spacing * rng.uniform(0.6f, 1.0f);
            d.scale = glm::vec3(long_scale, 0.1f * short_scale, short_scale);
            d.rgb = ground_colour(c, p, normal, rng);
            d.opacity_logit = rng.uniform(3.5f, 5.0f);
            synth::append_gaussian(cloud, d);
        }
}

void append_chunk_water(SplatCloud& cloud, const ContentContext& c, const ChunkSquare& square, synth::Rng& rng) {
    const WorldTerrain& t = *c.terrain;
    const Grid g = grid_for(square, kWaterSpacing / std::sqrt(c.density));
    // Rows far from the river are skipped before drawing: the river crosses few chunks.
    const float reach = WorldTerrain::kRiverHalfWidth + 2.0f * std::max(g.dx, g.dz);
    for (int iz = 0; iz < g.nz; ++iz) {
        const float row_z = square.lo.y + (static_cast<float>(iz) + 0.5f) * g.dz;
        const float centre = t.river_x(row_z);
        if (centre + 2.0f * reach < square.lo.x || centre - 2.0f * reach > square.hi.x) continue;
        for (int ix = 0; ix < g.nx; ++ix) {
            const float jx = rng.uniform(-0.35f, 0.35f);
            const float jz = rng.uniform(-0.35f, 0.35f);
            const glm::vec2 p(square.lo.x + (static_cast<float>(ix) + 0.5f + jx) * g.dx,
                              square.lo.y + (static_cast<float>(iz) + 0.5f + jz) * g.dz);
            const float distance = t.river_distance(p.x, p.y);
            const float highlight = rng.uniform();
            const float shade = rng.uniform(0.9f, 1.1f);
            if (distance > WorldTerrain::kRiverHalfWidth + 0.2f) continue;
            // Streaks along the flow: long in the direction the centre line runs.
            const glm::vec3 flow = glm::normalize(glm::vec3(t.river_x(p.y + 0.5f) - t.river_x(p.y - 0.5f), 0.0f, 1.0f));
            const float edge = distance / WorldTerrain::kRiverHalfWidth;
            synth::GaussianDraft d;
            d.position = glm::vec3(p.x, t.water_level(p.y), p.y);
            d.axis_x = flow;
            d.axis_y = glm::vec3(0.0f, 1.0f, 0.0f);
            const float spacing = std::max(g.dx, g.dz);
            d.scale = glm::vec3(1.1f * spacing, 0.02f, 0.6f * spacing);
            d.rgb = synth::mix_rgb({0.12f, 0.25f, 0.36f}, {0.24f, 0.37f, 0.42f}, edge * edge) * shade;
            if (highlight < 0.06f) d.rgb = glm::vec3(0.55f, 0.65f, 0.72f);  // glints of sky
            d.opacity_logit = 2.0f + highlight;
            synth::append_gaussian(cloud, d);
        }
    }
}

SplatCloud make_chunk_content(const ContentContext& c, const ChunkSquare& square, ContentCounts* counts) {
    // The chunk's own streams for its grids; objects use their placement cells' streams.
    const auto cell_x = static_cast<std::int64_t>(std::floor(square.lo.x));
    const auto cell_z = static_cast<std::int64_t>(std::floor(square.lo.y));
    SplatCloud cloud;
    ContentCounts local;
    synth::Rng ground_rng(c.seed, stream_id(StreamKind::ground, cell_x, cell_z));
    append_chunk_ground(cloud, c, square, ground_rng);
    local.ground = cloud.size();
    synth::Rng water_rng(c.seed, stream_id(StreamKind::water, cell_x, cell_z));
    append_chunk_water(cloud, c, square, water_rng);
    local.water = cloud.size() - local.ground;
    std::size_t before = cloud.size();
    append_chunk_rocks(cloud, c, square);
    local.rocks = cloud.size() - before;
    before = cloud.size();
    append_chunk_grass(cloud, c, square);
    local.grass = cloud.size() - before;
    append_chunk_trees(cloud, c, square, local);
    before = cloud.size();
    append_chunk_fences(cloud, c, square);
    local.fences = cloud.size() - before;
    if (counts) *counts = local;
    return cloud;
}

}  // namespace splat_lod::world
