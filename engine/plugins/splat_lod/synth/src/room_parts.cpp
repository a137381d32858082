// The room scene's surfaces: tiled panels, boxes and the paints that give them fine texture.
#include "splat_lod/synth/synth_common.h"

#include <algorithm>
#include <cmath>

#include "room_parts.h"

namespace splat_lod::synth::room {

void tile_panel(SplatCloud& cloud, const Panel& panel, float spacing, float detail, const Paint& paint, Rng& rng) {
    require_detail(detail, "make_room_scene");
    const float step = spacing / std::sqrt(detail);
    const float length_u = std::sqrt(glm::dot(panel.u, panel.u)), length_v = std::sqrt(glm::dot(panel.v, panel.v));
    const int nu = std::max(1, static_cast<int>(std::ceil(length_u / step)));
    const int nv = std::max(1, static_cast<int>(std::ceil(length_v / step)));
    require_count(static_cast<double>(nu) * static_cast<double>(nv), "make_room_scene");
    const glm::vec3 du = panel.u / static_cast<float>(nu), dv = panel.v / static_cast<float>(nv);
    const glm::vec3 axis_u = panel.u / length_u, axis_v = panel.v / length_v;
    const glm::vec3 normal = glm::cross(axis_u, axis_v);
    const float tile_u = length_u / static_cast<float>(nu), tile_v = length_v / static_cast<float>(nv);
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            // One draw per statement (synth_common.h).
            const float jitter_u = rng.uniform(-0.15f, 0.15f);
            const float jitter_v = rng.uniform(-0.15f, 0.15f);
            GaussianDraft g;
            g.position = panel.corner + du * (static_cast<float>(i) + 0.5f + jitter_u) +
                         dv * (static_cast<float>(j) + 0.5f + jitter_v);
            g.axis_x = axis_u;
            g.axis_y = axis_v;
            // 0.6 × the tile merges neighbours into a closed surface and keeps their colours apart.
            g.scale = glm::vec3(0.6f * tile_u, 0.6f * tile_v, 0.06f * std::min(tile_u, tile_v));
            g.rgb = paint(g.position, normal, rng);
            g.opacity_logit = rng.uniform(4.0f, 5.0f);
            append_gaussian(cloud, g);
        }
}

void tile_box(SplatCloud& cloud, const glm::vec3& lo, const glm::vec3& hi, float spacing, float detail,
              const Paint& paint, Rng& rng) {
    const glm::vec3 d = hi - lo;
    const Panel faces[5] = {
        {{lo.x, hi.y, hi.z}, {d.x, 0.0f, 0.0f}, {0.0f, 0.0f, -d.z}},  // top (+y)
        {{lo.x, lo.y, hi.z}, {d.x, 0.0f, 0.0f}, {0.0f, d.y, 0.0f}},   // front (+z)
        {{hi.x, lo.y, lo.z}, {-d.x, 0.0f, 0.0f}, {0.0f, d.y, 0.0f}},  // back (−z)
        {{lo.x, lo.y, lo.z}, {0.0f, 0.0f, d.z}, {0.0f, d.y, 0.0f}},   // left (−x)
        {{hi.x, lo.y, hi.z}, {0.0f, 0.0f, -d.z}, {0.0f, d.y, 0.0f}},  // right (+x)
    };
    for (const Panel& face : faces) tile_panel(cloud, face, spacing, detail, paint, rng);
}

float hash01(int a, int b, int c, std::uint64_t seed) {
    // Value noise at a lattice point is that point's hashed value.
    return value_noise_3d(glm::vec3(static_cast<float>(a), static_cast<float>(b), static_cast<float>(c)), seed);
}

namespace {

float fraction(float x) {
    return x - std::floor(x);
}

// The coordinate along a wall (x on walls facing z, z on walls facing x).
float along_wall(const glm::vec3& p) {
    return p.x + p.z;
}

glm::vec3 finish(const glm::vec3& rgb, const glm::vec3& normal, float ambient, Rng& rng) {
    return rgb * sun_shade(normal, ambient) * rng.uniform(0.94f, 1.06f);
}

}  // namespace

Paint floor_planks(std::uint64_t seed) {
    return [seed](const glm::vec3& p, const glm::vec3& n, Rng& rng) {
        constexpr float kPlank = 0.14f;
        const float across = (p.x + 10.0f) / kPlank;
        const int plank = static_cast<int>(std::floor(across));
        // Joints staggered from plank to plank; each board its own tone.
        const float offset = 1.7f * hash01(plank, 0, 0, seed);
        const int board = static_cast<int>(std::floor((p.z + offset + 20.0f) / 1.1f));
        const float tone = hash01(plank, board, 1, seed);
        glm::vec3 rgb = mix_rgb({0.42f, 0.28f, 0.17f}, {0.72f, 0.54f, 0.34f}, tone);
        rgb *= 0.82f + 0.36f * value_noise(p.x * 40.0f, p.z * 2.5f, seed + 7);
        if (std::min(fraction(across), 1.0f - fraction(across)) * kPlank < 0.012f) rgb *= 0.5f;
        return finish(rgb, n, 0.75f, rng);
    };
}

Paint rug_pattern(float x0, float z0, float x1, float z1) {
    return [=](const glm::vec3& p, const glm::vec3& n, Rng& rng) {
        const glm::vec3 cream(0.90f, 0.84f, 0.70f), red(0.62f, 0.12f, 0.10f), gold(0.85f, 0.66f, 0.22f),
            navy(0.10f, 0.14f, 0.36f);
        const float border = std::min(std::min(p.x - x0, x1 - p.x), std::min(p.z - z0, z1 - p.z));
        glm::vec3 rgb;
        if (border < 0.15f) {
            rgb = static_cast<int>(std::floor(border / 0.05f)) % 2 == 0 ? cream : red;
        } else {
            // Diamonds 12 cm across.
            const float d = std::abs(fraction(p.x / 0.12f) - 0.5f) + std::abs(fraction(p.z / 0.12f) - 0.5f);
            rgb = d < 0.2f ? gold : d < 0.38f ? red : navy;
        }
        return finish(rgb, n, 0.75f, rng);
    };
}

Paint striped_wallpaper() {
    return [](const glm::vec3& p, const glm::vec3& n, Rng& rng) {
        const float phase = fraction(along_wall(p) / 0.12f);
        glm::vec3 rgb = phase < 0.4f    ? glm::vec3(0.16f, 0.34f, 0.24f)
                        : phase < 0.47f ? glm::vec3(0.86f, 0.70f, 0.30f)
                                        : glm::vec3(0.88f, 0.83f, 0.68f);
        if (p.y < 0.9f)
            rgb = fraction(along_wall(p) / 0.1f) < 0.12f ? glm::vec3(0.22f, 0.14f, 0.08f)
                                                         : glm::vec3(0.50f, 0.33f, 0.20f);
        return finish(rgb, n, 0.8f, rng);
    };
}

Paint panelled_wall(std::uint64_t seed) {
    return [seed](const glm::vec3& p, const glm::vec3& n, Rng& rng) {
        glm::vec3 rgb;
        if (p.y < 1.0f) {
            // Vertical boards 10 cm wide with dark joints.
            const float across = along_wall(p) / 0.1f;
            const float tone = hash01(static_cast<int>(std::floor(across)), 3, 5, seed);
            rgb = mix_rgb({0.46f, 0.30f, 0.18f}, {0.62f, 0.44f, 0.28f}, tone);
            if (fraction(across) < 0.14f) rgb *= 0.45f;
        } else if (p.y < 1.06f) {
            rgb = glm::vec3(0.30f, 0.18f, 0.10f);  // the dado rail
        } else {
            rgb = glm::vec3(0.80f, 0.75f, 0.66f) * (0.88f + 0.24f * value_noise_3d(p * 1.5f, seed + 11));
        }
        return finish(rgb, n, 0.8f, rng);
    };
}

Paint plain(const glm::vec3& rgb, float variation, float ambient) {
    return [=](const glm::vec3&, const glm::vec3& n, Rng& rng) {
        return rgb * sun_shade(n, ambient) * rng.uniform(1.0f - variation, 1.0f + variation);
    };
}

Paint checker(const glm::vec3& a, const glm::vec3& b, float square) {
    return [=](const glm::vec3& p, const glm::vec3& n, Rng& rng) {
        const int parity =
            static_cast<int>(std::floor(p.x / square) + std::floor(p.y / square) + std::floor(p.z / square));
        return finish(parity % 2 == 0 ? a : b, n, 0.6f, rng);
    };
}

Paint fabric_stripes(const glm::vec3& a, const glm::vec3& b, float period) {
    return [=](const glm::vec3& p, const glm::vec3& n, Rng& rng) {
        return finish(fraction((p.x + p.y) / period) < 0.5f ? a : b, n, 0.6f, rng);
    };
}

Paint drawers(float y0, float drawer_height) {
    return [=](const glm::vec3& p, const glm::vec3& n, Rng& rng) {
        glm::vec3 rgb(0.55f, 0.38f, 0.22f);
        if (std::abs(n.x) > 0.5f) {
            const float in_drawer = std::fmod(p.y - y0, drawer_height);
            if (in_drawer < 0.012f || in_drawer > drawer_height - 0.012f) rgb = glm::vec3(0.12f, 0.08f, 0.05f);
            // A brass handle across the middle of each drawer.
            if (std::abs(in_drawer - 0.5f * drawer_height) < 0.015f && std::abs(fraction(p.z / 0.8f) - 0.5f) < 0.15f)
                rgb = glm::vec3(0.90f, 0.74f, 0.36f);
        }
        return finish(rgb, n, 0.6f, rng);
    };
}

Paint fine_stripes(float period) {
    return [=](const glm::vec3& p, const glm::vec3& n, Rng& rng) {
        const float phase = fraction((along_wall(p) + p.y) / period);
        const glm::vec3 rgb = phase < 0.33f   ? glm::vec3(0.85f, 0.20f, 0.15f)
                              : phase < 0.66f ? glm::vec3(0.95f, 0.90f, 0.80f)
                                              : glm::vec3(0.10f, 0.25f, 0.60f);
        return finish(rgb, n, 0.8f, rng);
    };
}

Paint rings(const glm::vec3& centre, float period) {
    return [=](const glm::vec3& p, const glm::vec3& n, Rng& rng) {
        const glm::vec3 d = p - centre;
        const int band = static_cast<int>(std::floor(std::sqrt(glm::dot(d, d)) / period)) % 3;
        const glm::vec3 rgb = band == 0   ? glm::vec3(0.95f, 0.80f, 0.20f)
                              : band == 1 ? glm::vec3(0.15f, 0.45f, 0.30f)
                                          : glm::vec3(0.10f, 0.08f, 0.12f);
        return finish(rgb, n, 0.8f, rng);
    };
}

}  // namespace splat_lod::synth::room
