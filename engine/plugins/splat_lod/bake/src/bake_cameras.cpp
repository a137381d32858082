#include "splat_lod/bake/bake_cameras.h"

#include <array>
#include <cmath>
#include <cstdio>

#include "engine/core/error.h"

namespace splat_lod::bake {
namespace {

constexpr float kPi = 3.14159265358979f;

// "rings:RxA" → (R, A), or false.
bool parse_rings(const std::string& spec, int& rings, int& per_ring) {
    if (spec == "auto") {
        rings = 3;
        per_ring = 8;
        return true;
    }
    if (spec.rfind("rings:", 0) != 0) return false;
    char tail = 0;
    if (std::sscanf(spec.c_str() + 6, "%dx%d%c", &rings, &per_ring, &tail) != 2 || rings < 1 || per_ring < 1 ||
        rings > 64 || per_ring > 256)
        engine::fail("bake cameras: \"" + spec + "\" is not rings:RxA with R in 1..64 and A in 1..256");
    return true;
}

}  // namespace

std::vector<eval::CameraPose> bake_camera_poses(const std::string& spec, const eval::SceneExtent& extent,
                                                const glm::vec3& up) {
    int rings = 0, per_ring = 0;
    if (!parse_rings(spec, rings, per_ring)) return eval::load_camera_set(spec, extent, up);
    if (!(glm::length(up) > 0.0f)) engine::fail("bake cameras: the up direction must not be zero");
    const glm::vec3 u = glm::normalize(up);
    const glm::vec3 a = glm::normalize(glm::cross(u, std::abs(u.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1)));
    const glm::vec3 b = glm::cross(u, a);
    const float distance = 2.2f * extent.radius;
    std::vector<eval::CameraPose> poses;
    for (int r = 0; r < rings; ++r) {
        const float elevation = rings == 3   ? std::array<float, 3>{-0.15f, 0.2f, 0.55f}[static_cast<std::size_t>(r)]
                                : rings == 1 ? 0.2f
                                             : -0.2f + 0.9f * static_cast<float>(r) / static_cast<float>(rings - 1);
        for (int j = 0; j < per_ring; ++j) {
            // Rings are offset by a fraction of the azimuth step so that no two share a meridian.
            const float azimuth = 2.0f * kPi *
                                  (static_cast<float>(j) + static_cast<float>(r) / static_cast<float>(rings)) /
                                  static_cast<float>(per_ring);
            const glm::vec3 dir =
                std::cos(elevation) * (std::cos(azimuth) * a + std::sin(azimuth) * b) + std::sin(elevation) * u;
            eval::CameraPose pose;
            pose.name = "bake ring " + std::to_string(r) + " view " + std::to_string(j);
            pose.eye = extent.centre + dir * distance;
            pose.forward = -dir;
            pose.up = glm::normalize(glm::cross(glm::cross(pose.forward, u), pose.forward));
            pose.fov_y = glm::radians(50.0f);
            pose.focus_distance = distance;
            poses.push_back(pose);
        }
    }
    return poses;
}

std::vector<reference::ReferenceCamera> bake_cameras(const std::vector<eval::CameraPose>& poses, int width,
                                                     int height) {
    if (width < 1 || height < 1) engine::fail("bake cameras: the image size must be positive");
    std::vector<reference::ReferenceCamera> cameras;
    cameras.reserve(poses.size());
    for (const auto& pose : poses)
        cameras.push_back(reference::make_reference_camera(eval::make_view(pose, width, height)));
    return cameras;
}

}  // namespace splat_lod::bake
