#include "splat_test_data.h"

#include <algorithm>
#include <cmath>

#include "test_support.h"

namespace engine::test {

std::vector<RealSplatScene> real_splat_scenes() {
    // biker, guitar and the donut are kept in tests/data; the SOG scenes only in ../shared/data.
    return {
        {"biker", data_file("splats/playcanvas-engine/biker.compressed.ply"), {0, -1, 0}},
        {"guitar", data_file("splats/playcanvas-engine/guitar.compressed.ply"), {0, -1, 0}},
        {"donut", data_file("splats/gshairlod-donut/fused.ply"), {0, 0, 1}},
        {"playbot", data_file("splats/playcanvas-engine/playbot-lod-sog/0_0/meta.json"), {0, -1, 0}},
        {"logo", data_file("splats/playcanvas-engine/playcanvas-logo-sog/meta.json"), {0, -1, 0}},
    };
}

std::vector<CameraView> orbit_cameras(const splat_lod::SplatCloud& cloud, const glm::vec3& up, int count, int width,
                                      int height, float distance_factor) {
    glm::vec3 centre;
    for (int axis = 0; axis < 3; ++axis) {
        std::vector<float> v;
        for (const auto& p : cloud.positions) v.push_back(p[axis]);
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        centre[axis] = v[v.size() / 2];
    }
    std::vector<float> d;
    for (const auto& p : cloud.positions) d.push_back(glm::length(p - centre));
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() * 9 / 10), d.end());
    const float radius = d[d.size() * 9 / 10];
    // A frame around `up`.
    const glm::vec3 u = glm::normalize(up);
    const glm::vec3 a = glm::normalize(glm::cross(u, std::abs(u.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1)));
    const glm::vec3 b = glm::cross(u, a);
    std::vector<CameraView> cameras;
    for (int i = 0; i < count; ++i) {
        const float azimuth = 0.6f + 2.0f * 3.14159265f * static_cast<float>(i) / static_cast<float>(count);
        const float elevation = (i % 2 == 0) ? 0.25f : -0.1f;
        const glm::vec3 dir =
            std::cos(elevation) * (std::cos(azimuth) * a + std::sin(azimuth) * b) + std::sin(elevation) * u;
        cameras.push_back(make_look_at_camera(centre + dir * radius * distance_factor, centre, u, glm::radians(50.0f),
                                              width, height, 0.01f, 1e5f));
    }
    return cameras;
}

std::vector<GaussianSpec> swirl_specs(int n, float colour_amplitude, float blue) {
    std::vector<GaussianSpec> specs;
    for (int i = 0; i < n; ++i) {
        const float t = static_cast<float>(i);
        specs.push_back({{std::sin(t * 1.7f), std::cos(t * 2.3f), std::sin(t * 0.37f) * 0.8f},
                         {-2.6f + 0.6f * std::sin(t), -2.4f + 0.5f * std::cos(t * 1.3f), -3.0f},
                         glm::normalize(glm::vec4(1.0f, std::sin(t), std::cos(t * 0.7f), 0.3f)),
                         std::sin(t * 0.91f) * 3.0f,
                         {0.5f + colour_amplitude * std::sin(t), 0.5f + colour_amplitude * std::cos(t), blue}});
    }
    return specs;
}

splat_lod::SplatCloud make_cloud(const std::vector<GaussianSpec>& specs) {
    splat_lod::SplatCloud cloud;
    cloud.resize(specs.size());
    for (std::size_t i = 0; i < specs.size(); ++i) {
        const auto& s = specs[i];
        cloud.positions[i] = s.position;
        cloud.log_scales[i] = s.log_scale;
        cloud.rotations[i] = {s.rotation[0], s.rotation[1], s.rotation[2], s.rotation[3]};
        cloud.opacity_logits[i] = s.opacity_logit;
        cloud.sh_dc[i] = (s.color - 0.5f) / splat_lod::kShC0;
    }
    return cloud;
}

splat_lod::SplatCloud lattice_cloud(int n) {
    std::vector<GaussianSpec> specs;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                GaussianSpec g;
                g.position = glm::vec3(x, y, z) / static_cast<float>(n - 1) - 0.5f;
                g.log_scale = glm::vec3(-4.0f);
                g.color = glm::vec3(0.2f + 0.3f * static_cast<float>(x % 3), 0.3f + 0.05f * static_cast<float>(y % 5),
                                    static_cast<float>((x + z) % 2));
                specs.push_back(g);
            }
    return make_cloud(specs);
}

}  // namespace engine::test
