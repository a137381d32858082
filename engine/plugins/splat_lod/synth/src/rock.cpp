// Rocks: lumpy ellipsoids skinned with flat Gaussians tangent to the surface.
#include "splat_lod/synth/synth_common.h"

#include <array>
#include <cmath>

namespace splat_lod::synth {
namespace {

constexpr float kRockGaussiansPerSquareMetre = 2500.0f;

// A few broad bumps and dents plus finer noise make the radius depend on direction, so no two
// rocks share a silhouette.
struct RockShape {
    std::array<glm::vec3, 6> bump_directions;
    std::array<float, 6> bump_amounts;
    std::uint64_t noise_seed = 0;

    explicit RockShape(Rng& rng) {
        for (std::size_t i = 0; i < bump_directions.size(); ++i) {
            bump_directions[i] = random_unit_vector(rng);
            bump_amounts[i] = rng.uniform(-0.18f, 0.28f);
        }
        noise_seed = rng.next_u64();
    }

    float radius_factor(const glm::vec3& direction) const {
        float r = 1.0f;
        for (std::size_t i = 0; i < bump_directions.size(); ++i) {
            const float d = std::max(0.0f, glm::dot(direction, bump_directions[i]));
            r += bump_amounts[i] * d * d * d;
        }
        return r * (0.92f + 0.16f * value_noise_3d(direction * 2.5f + glm::vec3(7.0f), noise_seed));
    }
};

glm::vec3 rock_colour(const glm::vec3& local, const glm::vec3& normal, std::uint64_t seed, Rng& rng) {
    const glm::vec3 grey(0.50f, 0.49f, 0.46f), brown_grey(0.45f, 0.40f, 0.34f), lichen(0.58f, 0.60f, 0.30f);
    const float mottling = value_noise_3d(local / 0.12f, seed + 1);
    glm::vec3 rgb = mix_rgb(grey, brown_grey, mottling);
    if (value_noise_3d(local / 0.05f, seed + 2) > 0.78f) rgb = mix_rgb(rgb, lichen, 0.7f);
    return rgb * sun_shade(normal, 0.55f) * rng.uniform(0.85f, 1.08f);
}

}  // namespace

IndexRange append_rock(SplatCloud& cloud, const glm::vec3& centre, const glm::vec3& half_extents, Rng& rng,
                       float detail) {
    require_finite(centre, "append_rock", "centre");
    require_positive(half_extents.x, "append_rock", "half_extents.x");
    require_positive(half_extents.y, "append_rock", "half_extents.y");
    require_positive(half_extents.z, "append_rock", "half_extents.z");
    require_detail(detail, "append_rock");
    const std::size_t begin = cloud.size();
    const RockShape shape(rng);
    const glm::vec3& e = half_extents;
    // Ellipsoid area by the mean of the pairwise axis products (within a few % for these aspect ratios).
    const float area = 4.0f * static_cast<float>(kPi) * (e.x * e.y + e.y * e.z + e.z * e.x) / 3.0f;
    const float density = kRockGaussiansPerSquareMetre * detail;
    require_count(static_cast<double>(area) * density, "append_rock");
    const auto samples = static_cast<std::size_t>(std::lround(area * density));
    const float spacing = 1.0f / std::sqrt(density);
    for (std::size_t s = 0; s < samples; ++s) {
        const glm::vec3 direction = random_unit_vector(rng);
        const glm::vec3 local = direction * half_extents * shape.radius_factor(direction);
        if (local.y < -0.02f * e.y) continue;  // buried: never seen
        // The ellipsoid's normal, ignoring the bumps: the Gaussians are small enough that the
        // difference does not show, and it keeps them lying flat on the surface.
        const glm::vec3 normal = glm::normalize(local / (half_extents * half_extents));
        GaussianDraft g;
        g.position = centre + local;
        g.axis_x = random_perpendicular(normal, rng);
        g.axis_y = glm::cross(normal, g.axis_x);
        const float size = spacing * rng.uniform(0.8f, 1.3f);
        g.scale = glm::vec3(size, size * rng.uniform(0.6f, 1.0f), 0.15f * size);
        // Darker towards the ground, where less sky reaches the stone.
        const float foot = glm::smoothstep(-0.05f, 0.6f, local.y / e.y);
        g.rgb = rock_colour(local, normal, shape.noise_seed, rng) * (0.65f + 0.35f * foot);
        g.opacity_logit = rng.uniform(3.5f, 5.0f);
        append_gaussian(cloud, g);
    }
    return {begin, cloud.size()};
}

}  // namespace splat_lod::synth
