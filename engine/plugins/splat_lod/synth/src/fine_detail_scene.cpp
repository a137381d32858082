// The fine-detail evaluation scene: a small garden whose foliage, fence and grass alias when the
// garden is seen small.
#include "splat_lod/synth/synth_common.h"

#include <array>

#include "splat_lod/synth/fine_detail_scene.h"

namespace splat_lod::synth {
namespace {

// The layout is fixed, so that evaluation cameras can be placed once; the seed changes every
// shape, colour and small offset.
struct TreeSlot {
    glm::vec3 base;
    float height;
    TreeKind kind;
};
constexpr float kGroundRadius = 5.0f;
const std::array<TreeSlot, 5> kTrees = {{
    {{-2.3f, 0.0f, -1.5f}, 5.6f, TreeKind::broadleaf},
    {{2.3f, 0.0f, -2.4f}, 6.0f, TreeKind::conifer},
    {{2.7f, 0.0f, 0.9f}, 3.6f, TreeKind::broadleaf},
    {{-3.4f, 0.0f, 1.4f}, 3.2f, TreeKind::conifer},
    {{0.2f, 0.0f, -3.5f}, 4.4f, TreeKind::broadleaf},
}};
// 7.8 m of fence across the front: 49 boards.
const glm::vec3 kFenceStart(-3.9f, 0.0f, 3.3f), kFenceEnd(3.9f, 0.0f, 3.3f);
constexpr float kFenceHeight = 0.9f;

struct GrassSlot {
    glm::vec3 centre;
    float radius;
};
constexpr float kGrassDensity = 1200.0f;  // blades per m²
const std::array<GrassSlot, 6> kGrass = {{
    {{-1.5f, 0.0f, 2.2f}, 1.4f},
    {{1.5f, 0.0f, 2.3f}, 1.2f},
    {{0.0f, 0.0f, 4.1f}, 0.8f},  // outside the fence, nearest the camera
    {{-2.6f, 0.0f, -0.3f}, 1.3f},
    {{2.9f, 0.0f, -1.0f}, 1.0f},
    {{0.4f, 0.0f, -1.0f}, 1.1f},
}};

struct RockSlot {
    glm::vec3 centre;
    glm::vec3 half_extents;
};
const std::array<RockSlot, 3> kRocks = {{
    {{-0.8f, 0.0f, 1.2f}, {0.45f, 0.30f, 0.35f}},
    {{3.3f, 0.0f, 2.1f}, {0.30f, 0.22f, 0.28f}},
    {{-1.2f, 0.0f, -2.7f}, {0.60f, 0.42f, 0.50f}},
}};

glm::vec3 jittered(const glm::vec3& p, float amount, Rng& rng) {
    const float dx = rng.uniform(-amount, amount);
    const float dz = rng.uniform(-amount, amount);
    return p + glm::vec3(dx, 0.0f, dz);
}

}  // namespace

SplatCloud make_fine_detail_scene(const FineDetailOptions& options) {
    require_detail(options.detail, "make_fine_detail_scene");
    const float detail = options.detail;
    SplatCloud cloud;
    // Every object draws from its own stream, so one object's Gaussian count (which depends on
    // detail) never shifts another object's random numbers.
    std::uint64_t stream = 0;
    Rng ground_rng(options.seed, stream++);
    append_ground(cloud, glm::vec3(0.0f), kGroundRadius, ground_rng, detail);
    for (const auto& rock : kRocks) {
        Rng rng(options.seed, stream++);
        const glm::vec3 centre = jittered(rock.centre, 0.15f, rng);
        append_rock(cloud, centre, rock.half_extents, rng, detail);
    }
    for (const auto& grass : kGrass) {
        Rng rng(options.seed, stream++);
        append_grass(cloud, grass.centre, grass.radius, kGrassDensity, rng, detail);
    }
    for (const auto& tree : kTrees) {
        Rng rng(options.seed, stream++);
        TreeStyle style;
        style.kind = tree.kind;
        style.detail = detail;
        // A touch of autumn on some trees, so that not every crown has the same hue.
        style.leaf_tint.x = rng.uniform(0.95f, 1.12f);
        style.leaf_tint.z = rng.uniform(0.85f, 1.0f);
        const glm::vec3 base = jittered(tree.base, 0.2f, rng);
        const float height = tree.height * rng.uniform(0.95f, 1.05f);
        append_tree(cloud, base, height, rng, style);
    }
    Rng fence_rng(options.seed, stream++);
    append_picket_fence(cloud, kFenceStart, kFenceEnd, kFenceHeight, fence_rng, detail);
    return cloud;
}

}  // namespace splat_lod::synth
