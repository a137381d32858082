// Bake cameras of a chunk (world/chunk_cameras.h).
#include "splat_lod/synth/synth_common.h"

#include "chunk_cameras.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace splat_lod::world {
namespace {

// Horizontal distance from the chunk's middle (in half-diagonals) and height above the ground
// under the eye (metres): a walker at the chunk's edge, low flight, and a high overview.
constexpr ChunkCameraRing kGroundRings[kChunkCameraRings] = {
    {1.4f, 1.7f, 0.0f}, {3.0f, 25.0f, 0.0f}, {6.0f, 80.0f, 0.0f}};
// An aerial capture has no detail at eye height: steep views from above, then oblique ones.
constexpr ChunkCameraRing kAerialRings[kChunkCameraRings] = {
    {1.0f, 0.0f, 1.5f}, {2.5f, 0.0f, 2.0f}, {5.0f, 0.0f, 2.5f}};

std::vector<eval::CameraPose> ring_poses(const GroundHeight& height, const ChunkSquare& square, float scale,
                                         const ChunkCameraRing (&rings)[kChunkCameraRings]) {
    const glm::vec2 middle = 0.5f * (square.lo + square.hi);
    const glm::vec2 span = square.hi - square.lo;
    const float half_diagonal = 0.5f * std::sqrt(glm::dot(span, span));
    // The mean ground height over a 3 × 3 sample of the square: where the views aim.
    float ground = 0.0f;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const glm::vec2 p = square.lo + span * glm::vec2(0.25f + 0.25f * static_cast<float>(i),
                                                             0.25f + 0.25f * static_cast<float>(j));
            ground += height(p.x, p.y) / 9.0f;
        }
    const glm::vec3 target(middle.x, ground + 1.5f * scale, middle.y);
    std::vector<eval::CameraPose> poses;
    for (int r = 0; r < kChunkCameraRings; ++r)
        for (int k = 0; k < kChunkCamerasPerRing; ++k) {
            // Rings are turned against each other so that no two views share an azimuth.
            const double azimuth = synth::kTwoPiF *
                                   (static_cast<double>(k) + static_cast<double>(r) / kChunkCameraRings) /
                                   kChunkCamerasPerRing;
            const synth::SinCos sc = synth::sin_cos(azimuth);
            const glm::vec2 at = middle + glm::vec2(sc.cos, sc.sin) * (rings[r].distance * half_diagonal);
            eval::CameraPose pose;
            pose.name = "chunk ring " + std::to_string(r) + " view " + std::to_string(k);
            pose.eye = glm::vec3(
                at.x, height(at.x, at.y) + rings[r].height * scale + rings[r].height_per_half_diagonal * half_diagonal,
                at.y);
            const glm::vec3 to_target = target - pose.eye;
            pose.focus_distance = std::sqrt(glm::dot(to_target, to_target));
            pose.forward = to_target / pose.focus_distance;
            const glm::vec3 side = glm::cross(pose.forward, glm::vec3(0.0f, 1.0f, 0.0f));
            pose.up = glm::normalize(glm::cross(side, pose.forward));
            pose.fov_y = static_cast<float>(kChunkCameraFovDeg * synth::kPi / 180.0);
            poses.push_back(pose);
        }
    return poses;
}

}  // namespace

std::vector<eval::CameraPose> chunk_camera_poses(const WorldTerrain& terrain, const ChunkSquare& square) {
    return ring_poses([&](float x, float z) { return terrain.height(x, z); }, square, 1.0f, kGroundRings);
}

std::vector<eval::CameraPose> capture_chunk_camera_poses(const GroundHeight& ground, const ChunkSquare& square,
                                                         float scale, bool aerial) {
    return ring_poses(ground, square, scale, aerial ? kAerialRings : kGroundRings);
}

std::size_t points_seen(const eval::CameraPose& pose, const std::vector<glm::vec3>& points, float aspect, float znear) {
    const glm::vec3 right = glm::normalize(glm::cross(pose.forward, pose.up));
    const glm::vec3 up = glm::cross(right, pose.forward);
    const float tan_y = std::tan(0.5f * pose.fov_y), tan_x = tan_y * aspect;
    std::size_t seen = 0;
    for (const glm::vec3& p : points) {
        const glm::vec3 d = p - pose.eye;
        const float z = glm::dot(d, pose.forward);
        if (z > znear && std::fabs(glm::dot(d, right)) <= tan_x * z && std::fabs(glm::dot(d, up)) <= tan_y * z) ++seen;
    }
    return seen;
}

std::vector<eval::CameraPose> chunk_training_poses(const std::vector<eval::CameraPose>& cameras,
                                                   const std::vector<glm::vec3>& fine, const ChunkSquare& square,
                                                   float aspect, float znear, std::size_t most) {
    if (cameras.empty() || fine.empty() || most == 0) return {};
    std::vector<glm::vec3> sample;
    const std::size_t stride = std::max<std::size_t>(1, fine.size() / 64);
    glm::vec3 middle(0.0f);
    for (std::size_t i = 0; i < fine.size(); i += stride) {
        sample.push_back(fine[i]);
        middle += fine[i];
    }
    middle /= static_cast<float>(sample.size());
    const float reach = 8.0f * glm::length(square.hi - square.lo);
    std::vector<std::pair<float, std::size_t>> seeing;  // (distance, camera)
    for (std::size_t c = 0; c < cameras.size(); ++c) {
        const float distance = glm::length(cameras[c].eye - middle);
        if (distance <= reach && 4 * points_seen(cameras[c], sample, aspect, znear) >= sample.size())
            seeing.emplace_back(distance, c);
    }
    std::sort(seeing.begin(), seeing.end());
    std::vector<eval::CameraPose> poses;
    const std::size_t n = std::min(most, seeing.size());
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t pick = n == 1 ? 0 : k * (seeing.size() - 1) / (n - 1);
        eval::CameraPose pose = cameras[seeing[pick].second];
        const float along = glm::dot(middle - pose.eye, pose.forward);
        pose.focus_distance = along > znear ? along : std::max(seeing[pick].first, znear);
        poses.push_back(pose);
    }
    return poses;
}

}  // namespace splat_lod::world
