// Trees: a bark skeleton of tapered limbs, then thousands of small flat leaves around it. Leaves
// are the finest, highest-contrast content of the scene (bright leaves against dark gaps and sky).
#include "splat_lod/synth/synth_common.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace splat_lod::synth {
namespace {

const glm::vec3 kUp(0.0f, 1.0f, 0.0f);

// Leaves per square metre of height² at detail 1: crowns grow with the square of the height, so
// this keeps the foliage equally dense on small and tall trees.
constexpr float kBroadleafLeavesPerHeightSquared = 650.0f;
constexpr float kConiferLeavesPerHeightSquared = 600.0f;
// Leaf long-axis σ at detail 1; it grows by 1/√detail (clamped to the documented range) so that
// thinned crowns stay as full.
constexpr float kLeafScaleLo = 0.012f;
constexpr float kLeafScaleHi = 0.024f;
// Bark tile size at detail 1.
constexpr float kBarkTile = 0.035f;

struct LeafClump {
    glm::vec3 centre{0.0f};
    float radius = 0.0f;
};

// The crown's ellipsoid: leaves are shaded by how far out and how sunward they sit in it.
struct Crown {
    glm::vec3 centre{0.0f};
    glm::vec3 radii{1.0f};
};

glm::vec3 bark_colour(Rng& rng) {
    return glm::vec3(0.30f, 0.22f, 0.15f) * rng.uniform(0.65f, 1.1f);
}

// A tapered cylinder from a (radius ra) to b (radius rb). Thick limbs are tiled around their
// circumference with Gaussians elongated along the limb; thin ones become one chain of needles
// whose round cross-section is the limb's.
void append_limb(SplatCloud& cloud, const glm::vec3& a, const glm::vec3& b, float ra, float rb, float detail,
                 Rng& rng) {
    const glm::vec3 span = b - a;
    const float length = glm::length(span);
    if (length < 1e-3f) return;
    const glm::vec3 axis = span / length;
    const float tile = kBarkTile / std::sqrt(detail);
    const float mean_radius = 0.5f * (ra + rb);
    const int around = static_cast<int>(std::lround(kTwoPiF * mean_radius / tile));
    GaussianDraft g;
    g.axis_x = axis;
    if (around < 4) {
        const float step = std::max(2.5f * mean_radius, 0.5f * tile);
        const int count = std::max(1, static_cast<int>(std::ceil(length / step)));
        for (int i = 0; i < count; ++i) {
            const float t = (static_cast<float>(i) + 0.5f) / static_cast<float>(count);
            const float r = ra + (rb - ra) * t;
            g.position = a + span * t;
            g.axis_y = any_perpendicular(axis);
            g.scale = glm::vec3(0.6f * length / static_cast<float>(count), r, r);
            g.rgb = bark_colour(rng) * 0.8f;
            g.opacity_logit = rng.uniform(3.5f, 5.0f);
            append_gaussian(cloud, g);
        }
        return;
    }
    const glm::vec3 e1 = any_perpendicular(axis);
    const glm::vec3 e2 = glm::cross(axis, e1);
    const int rings = std::max(1, static_cast<int>(std::ceil(length / (1.5f * tile))));
    for (int ring = 0; ring < rings; ++ring) {
        const float t = (static_cast<float>(ring) + 0.5f) / static_cast<float>(rings);
        const float r = ra + (rb - ra) * t;
        const glm::vec3 centre = a + span * t;
        const float phase = rng.uniform();  // staggered rings hide the tiling
        for (int j = 0; j < around; ++j) {
            const SinCos sc = sin_cos(static_cast<double>(kTwoPiF) * (j + phase) / around);
            const glm::vec3 radial = e1 * sc.cos + e2 * sc.sin;
            g.position = centre + radial * r;
            g.axis_y = e2 * sc.cos - e1 * sc.sin;
            const float tangential = kTwoPiF * r / static_cast<float>(around);
            g.scale = glm::vec3(0.7f * length / static_cast<float>(rings), 0.65f * tangential, 0.15f * tangential);
            g.rgb = bark_colour(rng) * sun_shade(radial, 0.4f);
            g.opacity_logit = rng.uniform(3.5f, 5.0f);
            append_gaussian(cloud, g);
        }
    }
}

glm::vec3 broadleaf_colour(Rng& rng) {
    const float pick = rng.uniform();
    const float brightness = rng.uniform(0.85f, 1.1f);
    if (pick < 0.06f) return glm::vec3(0.62f, 0.60f, 0.16f) * brightness;  // yellowing
    if (pick < 0.16f) return glm::vec3(0.07f, 0.16f, 0.05f) * brightness;  // deep shade
    const float hue = rng.uniform();
    return mix_rgb(glm::vec3(0.18f, 0.40f, 0.08f), glm::vec3(0.36f, 0.56f, 0.14f), hue) * brightness;
}

glm::vec3 conifer_colour(Rng& rng) {
    const float pick = rng.uniform();
    const float brightness = rng.uniform(0.85f, 1.1f);
    if (pick < 0.04f) return glm::vec3(0.36f, 0.30f, 0.13f) * brightness;  // dead needles
    if (pick < 0.14f) return glm::vec3(0.05f, 0.13f, 0.06f) * brightness;
    const float hue = rng.uniform();
    return mix_rgb(glm::vec3(0.10f, 0.26f, 0.12f), glm::vec3(0.20f, 0.38f, 0.16f), hue) * brightness;
}

// One flat leaf at `position`, facing a random direction. Inner leaves are darker (the crown
// shades them) and sunward ones lighter, which is what makes a crown read as a volume.
void append_leaf(SplatCloud& cloud, const glm::vec3& position, const Crown& crown, const glm::vec3& base_colour,
                 const TreeStyle& style, Rng& rng) {
    const glm::vec3 local = (position - crown.centre) / crown.radii;
    const float outer = std::min(1.0f, glm::length(local));
    const glm::vec3 normal = outer > 1e-3f ? local / glm::length(local) : kUp;
    const float shade = (0.45f + 0.55f * outer) * sun_shade(normal, 0.55f);
    const glm::vec3 facing = random_unit_vector(rng);
    GaussianDraft g;
    g.position = position;
    g.axis_x = random_perpendicular(facing, rng);
    g.axis_y = glm::cross(facing, g.axis_x);
    const float size_factor = 1.0f / std::sqrt(style.detail);
    const float length =
        std::clamp(rng.uniform(kLeafScaleLo, kLeafScaleHi) * size_factor, kLeafScaleMin, kLeafScaleMax);
    g.scale = glm::vec3(length, length * rng.uniform(0.5f, 0.9f), 0.1f * length);
    g.rgb = base_colour * style.leaf_tint * shade;
    g.opacity_logit = rng.uniform(kLeafOpacityLogitMin, kLeafOpacityLogitMax);
    append_gaussian(cloud, g);
}

glm::vec3 horizontal_direction(double angle) {
    const SinCos sc = sin_cos(angle);
    return glm::vec3(sc.cos, 0.0f, sc.sin);
}

// A slightly leaning unit axis for a trunk.
glm::vec3 trunk_axis(float max_lean, Rng& rng) {
    const glm::vec3 lean_direction = random_perpendicular(kUp, rng);
    const float lean = rng.uniform(0.0f, max_lean);
    return glm::normalize(kUp + lean_direction * lean);
}

// The bark of a broadleaf tree: a trunk forking into 5–7 arched branches, each with two twigs,
// and a leader; returns the crown and a leaf clump at every branch, twig and leader tip.
std::vector<LeafClump> append_broadleaf_skeleton(SplatCloud& cloud, const glm::vec3& base, float height, float detail,
                                                 Rng& rng, Crown& crown) {
    const float trunk_radius = 0.03f * height * rng.uniform(0.9f, 1.1f);
    const glm::vec3 axis = trunk_axis(0.06f, rng);
    const glm::vec3 trunk_top = base + axis * (height * rng.uniform(0.38f, 0.46f));
    const glm::vec3 kink = random_perpendicular(kUp, rng);
    const glm::vec3 trunk_mid = 0.5f * (base + trunk_top) + kink * (0.02f * height);
    append_limb(cloud, base, trunk_mid, trunk_radius * 1.1f, trunk_radius * 0.85f, detail, rng);
    append_limb(cloud, trunk_mid, trunk_top, trunk_radius * 0.85f, trunk_radius * 0.7f, detail, rng);

    crown.centre = base + axis * (0.64f * height);
    const float crown_x = height * rng.uniform(0.27f, 0.32f);
    const float crown_z = height * rng.uniform(0.27f, 0.32f);
    crown.radii = glm::vec3(crown_x, 0.34f * height, crown_z);
    std::vector<LeafClump> clumps;
    const int branches = rng.uniform_int(5, 7);
    const double first_azimuth = rng.uniform(0.0f, kTwoPiF);
    for (int k = 0; k < branches; ++k) {
        const glm::vec3 out = horizontal_direction(first_azimuth + kTwoPiF * (k + rng.uniform(-0.3f, 0.3f)) / branches);
        const glm::vec3 origin = trunk_mid + (trunk_top - trunk_mid) * rng.uniform(0.4f, 1.0f);
        const float spread = crown.radii.x * rng.uniform(0.45f, 0.75f);
        const float rise = crown.radii.y * rng.uniform(-0.25f, 0.45f);
        const glm::vec3 tip = crown.centre + out * spread + kUp * rise;
        // Branches arch upwards before they spread.
        const glm::vec3 knee = 0.5f * (origin + tip) + kUp * (0.06f * height);
        append_limb(cloud, origin, knee, 0.45f * trunk_radius, 0.3f * trunk_radius, detail, rng);
        append_limb(cloud, knee, tip, 0.3f * trunk_radius, 0.1f * trunk_radius, detail, rng);
        clumps.push_back({tip, crown.radii.x * rng.uniform(0.38f, 0.5f)});
        for (int twig = 0; twig < 2; ++twig) {
            const glm::vec3 side = random_perpendicular(glm::normalize(tip - knee), rng);
            const glm::vec3 twig_tip = 0.5f * (knee + tip) + side * (crown.radii.x * rng.uniform(0.25f, 0.4f));
            append_limb(cloud, knee, twig_tip, 0.12f * trunk_radius, 0.05f * trunk_radius, detail, rng);
            clumps.push_back({twig_tip, crown.radii.x * rng.uniform(0.28f, 0.38f)});
        }
    }
    const glm::vec3 leader_tip = crown.centre + kUp * (0.55f * crown.radii.y);
    append_limb(cloud, trunk_top, leader_tip, 0.5f * trunk_radius, 0.1f * trunk_radius, detail, rng);
    clumps.push_back({leader_tip, 0.45f * crown.radii.x});
    return clumps;
}

TreeSplats append_broadleaf(SplatCloud& cloud, const glm::vec3& base, float height, Rng& rng, const TreeStyle& style) {
    TreeSplats result;
    result.bark.begin = cloud.size();
    Crown crown;
    const std::vector<LeafClump> clumps = append_broadleaf_skeleton(cloud, base, height, style.detail, rng, crown);
    result.bark.end = result.leaves.begin = cloud.size();

    // Leaves shared out by clump volume (radius³), concentrated towards each clump's surface.
    float total_volume = 0.0f;
    for (const auto& clump : clumps) total_volume += clump.radius * clump.radius * clump.radius;
    const float leaves = kBroadleafLeavesPerHeightSquared * style.detail * height * height;
    for (const auto& clump : clumps) {
        const float share = clump.radius * clump.radius * clump.radius / total_volume;
        const auto count = static_cast<int>(std::lround(leaves * share));
        for (int i = 0; i < count; ++i) {
            const float u = rng.uniform();
            const float reach = clump.radius * (1.0f - 0.6f * u * u);
            const glm::vec3 offset = random_unit_vector(rng) * reach * glm::vec3(1.0f, 0.8f, 1.0f);
            const glm::vec3 colour = broadleaf_colour(rng);
            append_leaf(cloud, clump.centre + offset, crown, colour, style, rng);
        }
    }
    result.leaves.end = cloud.size();
    return result;
}

// A conifer: the trunk and its whorls of branches, and the tier of foliage each whorl carries.
struct Tier {
    float along = 0.0f;  // distance up the trunk
    float radius = 0.0f;
};

struct ConiferSkeleton {
    glm::vec3 base{0.0f};
    glm::vec3 axis{0.0f, 1.0f, 0.0f};
    std::vector<Tier> tiers;
    float tier_spacing = 0.0f;
    Crown crown;

    glm::vec3 trunk_at(float along) const { return base + axis * along; }
};

ConiferSkeleton append_conifer_skeleton(SplatCloud& cloud, const glm::vec3& base, float height, float detail,
                                        Rng& rng) {
    ConiferSkeleton tree;
    tree.base = base;
    const float trunk_radius = 0.022f * height * rng.uniform(0.9f, 1.1f);
    tree.axis = trunk_axis(0.03f, rng);
    const float r = trunk_radius;
    append_limb(cloud, base, tree.trunk_at(0.4f * height), 1.1f * r, 0.75f * r, detail, rng);
    append_limb(cloud, tree.trunk_at(0.4f * height), tree.trunk_at(0.75f * height), 0.75f * r, 0.4f * r, detail, rng);
    append_limb(cloud, tree.trunk_at(0.75f * height), tree.trunk_at(height), 0.4f * r, 0.08f * r, detail, rng);

    const float crown_bottom = height * rng.uniform(0.12f, 0.2f);
    const float bottom_radius = height * rng.uniform(0.22f, 0.27f);
    tree.crown.centre = tree.trunk_at(0.5f * (crown_bottom + height));
    tree.crown.radii = glm::vec3(bottom_radius, 0.5f * (height - crown_bottom), bottom_radius);
    const int whorl_count = std::max(4, static_cast<int>(std::lround(2.2f * height)));
    tree.tier_spacing = (0.97f * height - crown_bottom) / static_cast<float>(whorl_count);
    for (int k = 0; k < whorl_count; ++k) {
        const float t = static_cast<float>(k) / static_cast<float>(whorl_count);
        const float along = crown_bottom + tree.tier_spacing * static_cast<float>(k);
        const float radius = bottom_radius * (1.0f - t) * rng.uniform(0.88f, 1.05f) + 0.02f * height;
        tree.tiers.push_back({along, radius});
        const int branches = rng.uniform_int(5, 7);
        const double first_azimuth = rng.uniform(0.0f, kTwoPiF);
        for (int b = 0; b < branches; ++b) {
            const glm::vec3 out =
                horizontal_direction(first_azimuth + kTwoPiF * (b + rng.uniform(-0.25f, 0.25f)) / branches);
            const glm::vec3 root = tree.trunk_at(along);
            const glm::vec3 tip = root + out * (0.9f * radius) - kUp * (0.25f * radius);
            append_limb(cloud, root, tip, 0.3f * trunk_radius * (1.0f - t) + 0.004f, 0.003f, detail, rng);
        }
    }
    return tree;
}

TreeSplats append_conifer(SplatCloud& cloud, const glm::vec3& base, float height, Rng& rng, const TreeStyle& style) {
    TreeSplats result;
    result.bark.begin = cloud.size();
    const ConiferSkeleton tree = append_conifer_skeleton(cloud, base, height, style.detail, rng);
    result.bark.end = result.leaves.begin = cloud.size();

    // Each tier is a drooping skirt: thick next to the trunk, where it reaches up to the next
    // whorl, thin and lower at its rim. Leaves are shared by tier area (radius²).
    float total_area = 0.0f;
    for (const auto& tier : tree.tiers) total_area += tier.radius * tier.radius;
    const float leaves = kConiferLeavesPerHeightSquared * style.detail * height * height;
    for (const auto& tier : tree.tiers) {
        const auto count = static_cast<int>(std::lround(leaves * tier.radius * tier.radius / total_area));
        for (int i = 0; i < count; ++i) {
            const float u = rng.uniform();
            const float reach = 1.0f - 0.8f * u * u;
            const glm::vec3 out = random_perpendicular(kUp, rng);
            const float rise = 1.2f * tree.tier_spacing * (1.0f - reach) * rng.uniform() - 0.28f * tier.radius * reach;
            const glm::vec3 position = tree.trunk_at(tier.along) + out * (tier.radius * reach) + kUp * rise;
            const glm::vec3 colour = conifer_colour(rng);
            append_leaf(cloud, position, tree.crown, colour, style, rng);
        }
    }
    result.leaves.end = cloud.size();
    return result;
}

}  // namespace

TreeSplats append_tree(SplatCloud& cloud, const glm::vec3& base, float height, Rng& rng, const TreeStyle& style) {
    require_finite(base, "append_tree", "base");
    require_positive(height, "append_tree", "height");
    require_finite(style.leaf_tint, "append_tree", "style.leaf_tint");
    require_detail(style.detail, "append_tree");
    require_count(1.3 * kBroadleafLeavesPerHeightSquared * style.detail * height * height, "append_tree");
    return style.kind == TreeKind::conifer ? append_conifer(cloud, base, height, rng, style)
                                           : append_broadleaf(cloud, base, height, rng, style);
}

}  // namespace splat_lod::synth
