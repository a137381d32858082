// Ground and grass: the surfaces everything else stands on.
#include "splat_lod/synth/synth_common.h"

#include <algorithm>
#include <cmath>

namespace splat_lod::synth {
namespace {

// The jittered grid spacing of the ground at detail 1 (400 Gaussians per m²): fine enough that a
// close camera sees soil texture rather than single blobs.
constexpr float kGroundSpacing = 0.05f;

glm::vec3 ground_colour(float x, float z, std::uint64_t seed, Rng& rng) {
    const glm::vec3 earth(0.40f, 0.30f, 0.20f), moss(0.30f, 0.36f, 0.16f), dark_soil(0.22f, 0.17f, 0.12f);
    // Metre-scale patches of moss and decimetre-scale darker soil, then per-Gaussian grain.
    const float moss_amount = glm::smoothstep(0.35f, 0.75f, value_noise(x / 0.9f, z / 0.9f, seed));
    const float dark_amount = 0.6f * glm::smoothstep(0.45f, 0.9f, value_noise(x / 0.22f, z / 0.22f, seed + 1));
    const glm::vec3 base = mix_rgb(mix_rgb(earth, moss, moss_amount), dark_soil, dark_amount);
    return base * rng.uniform(0.82f, 1.12f);
}

}  // namespace

IndexRange append_ground(SplatCloud& cloud, const glm::vec3& centre, float radius, Rng& rng, float detail) {
    require_finite(centre, "append_ground", "centre");
    require_positive(radius, "append_ground", "radius");
    require_detail(detail, "append_ground");
    const std::size_t begin = cloud.size();
    // A small disc at low detail still gets a few Gaussians across, or it would vanish.
    const float spacing = std::min(kGroundSpacing / std::sqrt(detail), 0.5f * radius);
    require_count(3.2 * (radius / spacing) * (radius / spacing), "append_ground");
    const int half_cells = static_cast<int>(std::ceil(radius / spacing));
    const std::uint64_t noise_seed = rng.next_u64();
    for (int iz = -half_cells; iz <= half_cells; ++iz) {
        for (int ix = -half_cells; ix <= half_cells; ++ix) {
            // Jitter below half a cell keeps every cell occupied, and the scales (0.6–1.15 ×
            // spacing) overlap the neighbours, so the disc has no holes at any view distance.
            const float x = (static_cast<float>(ix) + rng.uniform(-0.35f, 0.35f)) * spacing;
            const float z = (static_cast<float>(iz) + rng.uniform(-0.35f, 0.35f)) * spacing;
            if (x * x + z * z > radius * radius) continue;
            const glm::vec3 yaw = random_perpendicular(glm::vec3(0.0f, 1.0f, 0.0f), rng);
            GaussianDraft g;
            // Slightly below the plane, never above it, so that grass roots and rock feet stay in front.
            g.position = centre + glm::vec3(x, -rng.uniform(0.0f, 0.004f), z);
            g.axis_x = yaw;
            g.axis_y = glm::vec3(0.0f, 1.0f, 0.0f);
            const float long_scale = spacing * rng.uniform(0.75f, 1.15f);
            const float short_scale = spacing * rng.uniform(0.6f, 1.0f);
            g.scale = glm::vec3(long_scale, 0.1f * short_scale, short_scale);
            g.rgb = ground_colour(centre.x + x, centre.z + z, noise_seed, rng);
            g.opacity_logit = rng.uniform(3.5f, 5.0f);
            append_gaussian(cloud, g);
        }
    }
    return {begin, cloud.size()};
}

namespace {

glm::vec3 grass_colour(Rng& rng) {
    const float pick = rng.uniform();
    if (pick < 0.08f) return glm::vec3(0.55f, 0.55f, 0.22f) * rng.uniform(0.85f, 1.1f);  // dry blades
    if (pick < 0.18f) return glm::vec3(0.12f, 0.26f, 0.07f) * rng.uniform(0.85f, 1.1f);  // shaded blades
    const glm::vec3 a(0.26f, 0.48f, 0.12f), b(0.36f, 0.58f, 0.16f);
    const float hue = rng.uniform();
    return mix_rgb(a, b, hue) * rng.uniform(0.8f, 1.1f);
}

// A blade as two needle Gaussians: a straighter lower segment and an upper one that leans
// further, so that blades curve instead of standing like sticks.
void append_blade(SplatCloud& cloud, const glm::vec3& root, float height, Rng& rng) {
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const glm::vec3 lean_direction = random_perpendicular(up, rng);
    const float lower_lean = rng.uniform(0.0f, 0.35f);
    const float upper_lean = lower_lean + rng.uniform(0.1f, 0.7f);
    const glm::vec3 lower_axis = glm::normalize(up + lean_direction * lower_lean);
    const glm::vec3 upper_axis = glm::normalize(up + lean_direction * upper_lean);
    const glm::vec3 width_axis = glm::normalize(glm::cross(lean_direction, up));
    const float lower_length = 0.55f * height, upper_length = 0.45f * height;
    const float width = rng.uniform(0.0025f, 0.004f);
    const glm::vec3 colour = grass_colour(rng);
    const float opacity_logit = rng.uniform(2.5f, 4.5f);

    GaussianDraft g;
    g.axis_y = width_axis;
    g.opacity_logit = opacity_logit;
    // σ of a third of the segment length lets neighbouring segments overlap into one blade.
    g.position = root + lower_axis * (0.5f * lower_length);
    g.axis_x = lower_axis;
    g.scale = glm::vec3(lower_length / 3.0f, width, 0.15f * width);
    g.rgb = colour * 0.7f;  // the base of a blade is shaded by its neighbours
    append_gaussian(cloud, g);

    g.position = root + lower_axis * lower_length + upper_axis * (0.5f * upper_length);
    g.axis_x = upper_axis;
    g.scale = glm::vec3(upper_length / 3.0f, 0.7f * width, 0.15f * width);
    g.rgb = colour * 1.08f + glm::vec3(0.03f, 0.03f, 0.0f);
    append_gaussian(cloud, g);
}

}  // namespace

IndexRange append_grass(SplatCloud& cloud, const glm::vec3& centre, float radius, float density, Rng& rng,
                        float detail) {
    require_finite(centre, "append_grass", "centre");
    require_positive(radius, "append_grass", "radius");
    require_positive(density, "append_grass", "density");
    require_detail(detail, "append_grass");
    require_count(2.0 * density * detail * kPi * radius * radius, "append_grass");
    const std::size_t begin = cloud.size();
    const auto blades =
        static_cast<std::size_t>(std::lround(density * detail * static_cast<float>(kPi) * radius * radius));
    const std::uint64_t clump_seed = rng.next_u64();
    const std::uint64_t rim_seed = rng.next_u64();
    for (std::size_t b = 0; b < blades; ++b) {
        glm::vec2 offset;
        do {
            offset.x = rng.uniform(-1.0f, 1.0f);
            offset.y = rng.uniform(-1.0f, 1.0f);
        } while (glm::dot(offset, offset) > 1.0f);
        // A ragged rim: the patch's reach depends on direction (0.7–1 × radius), so patches do
        // not end in circles; blades also get shorter towards the rim, fading into the ground.
        const float distance = glm::length(offset);
        if (distance > 1e-6f) {
            const glm::vec2 direction = offset / distance;
            offset *= radius * (0.7f + 0.3f * value_noise(2.0f * direction.x, 2.0f * direction.y, rim_seed));
        }
        const float clump = value_noise((centre.x + offset.x) / 0.3f, (centre.z + offset.y) / 0.3f, clump_seed);
        const float edge = 1.0f - 0.5f * glm::smoothstep(0.6f, 1.0f, distance);
        const float height = (0.06f + 0.22f * (0.5f * rng.uniform() + 0.5f * clump)) * edge;
        append_blade(cloud, centre + glm::vec3(offset.x, 0.0f, offset.y), height, rng);
    }
    return {begin, cloud.size()};
}

}  // namespace splat_lod::synth
