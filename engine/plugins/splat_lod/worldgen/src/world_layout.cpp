// Houses, fences and posts along the path (world/world_layout.h).
#include "splat_lod/synth/synth_common.h"

#include "world_layout.h"

#include <algorithm>
#include <cmath>

#include "splat_lod/synth/world_streams.h"

namespace splat_lod::world {
namespace {

// The house mesh's footprint (world_meshes.cpp): 6 m wide (x), 5 m deep (z), eaves included.
constexpr float kHouseHalfWidth = 3.3f;
constexpr float kHouseHalfDepth = 2.8f;
constexpr float kHouseKeepOut = 7.0f;    // radius around a house kept free of trees and rocks
constexpr float kHouseSpacing = 110.0f;  // mean distance along x between house candidates
constexpr float kGardenDepth = 4.5f;     // from the house front to its picket fence
constexpr float kGardenHalfWidth = 4.0f;
constexpr float kPostSpacing = 40.0f;
constexpr float kFenceSegment = 2.5f;  // the fence mesh's length along its local x

// A yaw's front (+z turned) and right (+x turned) directions on the ground plane.
struct Frame2 {
    glm::vec2 front, right;
};

Frame2 frame_of(float yaw_deg) {
    const synth::SinCos sc = synth::sin_cos(static_cast<double>(yaw_deg) * synth::kPi / 180.0);
    return {{sc.sin, sc.cos}, {sc.cos, -sc.sin}};
}

float distance_to_segment(const glm::vec2& p, const glm::vec2& a, const glm::vec2& b) {
    const glm::vec2 ab = b - a;
    const float length2 = glm::dot(ab, ab);
    const float t = length2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / length2, 0.0f, 1.0f) : 0.0f;
    const glm::vec2 d = p - (a + ab * t);
    return std::sqrt(glm::dot(d, d));
}

struct LayoutBuilder {
    const WorldTerrain& terrain;
    WorldLayout layout;
    float half;  // half the world size

    bool inside(const glm::vec2& p, float margin) const {
        return std::abs(p.x) < half - margin && std::abs(p.y) < half - margin;
    }
    glm::vec3 on_ground(const glm::vec2& p) const { return {p.x, terrain.height(p.x, p.y), p.y}; }
    // A point beside the path at x: `side` (±1) picks the left or right of the direction of travel.
    glm::vec2 beside_path(float x, float side, float offset) const {
        const glm::vec2 along = terrain.path_direction(x);
        return glm::vec2(x, terrain.path_z(x)) + glm::vec2(-along.y, along.x) * (side * offset);
    }
    void add_prop(const char* mesh, const glm::vec3& at, float yaw_deg, const glm::vec3& scale = glm::vec3(1.0f)) {
        layout.props.push_back({mesh, at, glm::vec3(0.0f, yaw_deg, 0.0f), scale});
    }

    bool try_house(float x, synth::Rng& rng);
    // Each of these places its props along the stretch [from, to) of x.
    void houses(float from, float to, synth::Rng& rng);
    void posts(float from, float to);
    void fence_runs(float from, float to, synth::Rng& rng);
};

bool LayoutBuilder::try_house(float x, synth::Rng& rng) {
    const float side = rng.chance(0.5f) ? 1.0f : -1.0f;
    const float offset = rng.uniform(13.0f, 18.0f);
    const glm::vec2 centre = beside_path(x, side, offset);
    const float yaw = yaw_degrees(glm::vec2(x, terrain.path_z(x)) - centre);  // the front faces the path
    if (!inside(centre, 15.0f) || terrain.river_distance(centre.x, centre.y) < WorldTerrain::kRiverHalfWidth + 14.0f ||
        layout.blocked(centre, 12.0f))
        return false;
    const Frame2 f = frame_of(yaw);
    float lowest = terrain.height(centre.x, centre.y), highest = lowest;
    for (const float u : {-1.0f, 1.0f})
        for (const float v : {-1.0f, 1.0f}) {
            const glm::vec2 corner = centre + f.right * (u * kHouseHalfWidth) + f.front * (v * kHouseHalfDepth);
            const float h = terrain.height(corner.x, corner.y);
            lowest = std::min(lowest, h);
            highest = std::max(highest, h);
        }
    if (highest - lowest > 2.5f) return false;  // too steep for a house on a flat floor
    // Standing on its lowest corner, the uphill side sinks into the ground instead of floating.
    add_prop(kHouseMesh, glm::vec3(centre.x, lowest, centre.y), yaw);
    layout.keep_out.push_back({centre, centre, kHouseKeepOut});

    const glm::vec2 garden = centre + f.front * (kHouseHalfDepth + kGardenDepth);
    const glm::vec2 start = garden - f.right * kGardenHalfWidth, end = garden + f.right * kGardenHalfWidth;
    PicketFenceSpec fence;
    fence.start = on_ground(start);
    fence.end = on_ground(end);
    fence.index = static_cast<std::int64_t>(layout.picket_fences.size());
    layout.picket_fences.push_back(fence);
    layout.keep_out.push_back({start, end, 1.0f});
    return true;
}

void LayoutBuilder::houses(float from, float to, synth::Rng& rng) {
    for (float x = from + 30.0f + rng.uniform(0.0f, 60.0f); x < to - 30.0f;
         x += kHouseSpacing + rng.uniform(-30.0f, 30.0f))
        try_house(x, rng);
}

void LayoutBuilder::posts(float from, float to) {
    float side = 1.0f;
    for (float x = from + 10.0f; x < to - 10.0f; x += kPostSpacing, side = -side) {
        const glm::vec2 at = beside_path(x, side, WorldTerrain::kPathHalfWidth + 0.9f);
        if (!inside(at, 2.0f) || terrain.river_distance(at.x, at.y) < WorldTerrain::kRiverHalfWidth + 3.0f ||
            layout.blocked(at, 1.0f))
            continue;
        add_prop(kPostMesh, on_ground(at), yaw_degrees(terrain.path_direction(x)));
        layout.keep_out.push_back({at, at, 0.6f});
    }
}

// Runs of 6–14 fence segments beside the path, each segment a chord between two points beside it.
void LayoutBuilder::fence_runs(float from, float to, synth::Rng& rng) {
    float x = from + 20.0f + rng.uniform(0.0f, 80.0f);
    while (x < to - 20.0f) {
        const int segments = rng.uniform_int(6, 14);
        const float side = rng.chance(0.5f) ? 1.0f : -1.0f;
        const float offset = WorldTerrain::kPathHalfWidth + 2.2f;
        for (int k = 0; k < segments && x < to - 20.0f; ++k) {
            const float next = x + kFenceSegment * terrain.path_direction(x).x;
            const glm::vec2 a = beside_path(x, side, offset), b = beside_path(next, side, offset);
            x = next;
            const glm::vec2 middle = 0.5f * (a + b), chord = b - a;
            if (!inside(middle, 3.0f) ||
                terrain.river_distance(middle.x, middle.y) < WorldTerrain::kRiverHalfWidth + 2.0f ||
                layout.blocked(middle, 1.5f))
                continue;
            // The mesh's +x runs along the chord: its +z is the chord turned a quarter to the left.
            const float length = std::sqrt(glm::dot(chord, chord));
            add_prop(kFenceMesh, on_ground(middle), yaw_degrees(glm::vec2(-chord.y, chord.x)),
                     glm::vec3(length / kFenceSegment, 1.0f, 1.0f));
            layout.keep_out.push_back({a, b, 0.8f});
        }
        x += rng.uniform(60.0f, 160.0f);
    }
}

}  // namespace

float yaw_degrees(const glm::vec2& direction) {
    return static_cast<float>(std::round(std::atan2(direction.x, direction.y) * 180.0 / synth::kPi));
}

bool WorldLayout::blocked(const glm::vec2& p, float margin) const {
    return std::any_of(keep_out.begin(), keep_out.end(),
                       [&](const KeepOut& k) { return distance_to_segment(p, k.a, k.b) < k.radius + margin; });
}

WorldLayout make_world_layout(const WorldTerrain& terrain, std::uint64_t seed) {
    const float half = 0.5f * terrain.size(), middle = 0.5f * terrain.feature_scale();
    LayoutBuilder builder{terrain, {}, half};
    // From the west edge of the feature scale's middle square (world_terrain.h) to the east edge of the
    // world, then, in a larger world, the stretch west of that square from streams of their own: the
    // middle square has the props of a world of the feature scale's size, save at its east end, where
    // the larger world goes on.
    synth::Rng house_rng(seed, stream_id(StreamKind::layout, 0, 0));
    builder.houses(-middle, half, house_rng);
    synth::Rng west_house_rng(seed, stream_id(StreamKind::layout, 2, 0));
    builder.houses(-half, -middle, west_house_rng);
    builder.posts(-middle, half);
    builder.posts(-half, -middle);
    synth::Rng fence_rng(seed, stream_id(StreamKind::layout, 1, 0));
    builder.fence_runs(-middle, half, fence_rng);
    synth::Rng west_fence_rng(seed, stream_id(StreamKind::layout, 3, 0));
    builder.fence_runs(-half, -middle, west_fence_rng);
    return std::move(builder.layout);
}

}  // namespace splat_lod::world
