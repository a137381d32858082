#include "splat_lod/bake/bake_cameras.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "engine/core/error.h"

namespace splat_lod::bake {
namespace {

constexpr float kPi = 3.14159265358979f;
// The grid's turns at its outer columns and rows (grid_poses).
constexpr float kGridYawDeg = 20.0f;
constexpr float kGridPitchDeg = 10.0f;

// "AxB" or "AxBxC" after `prefix` → the numbers, each checked against [1, limit]; nullopt when the
// spec does not start with `prefix`. Throws naming the spec and `form` otherwise.
std::optional<std::vector<int>> parse_counts(const std::string& spec, const std::string& prefix,
                                             const std::vector<int>& limits, std::size_t required,
                                             const std::string& form) {
    if (spec.rfind(prefix, 0) != 0) return std::nullopt;
    std::vector<int> counts;
    const char* p = spec.c_str() + prefix.size();
    const char* end = spec.c_str() + spec.size();
    bool ok = true;
    while (ok && counts.size() < limits.size()) {
        int value = 0;
        const auto [next, error] = std::from_chars(p, end, value);
        ok = error == std::errc() && value >= 1 && value <= limits[counts.size()];
        counts.push_back(value);
        p = next;
        if (p == end || *p != 'x') break;
        ++p;
    }
    if (!ok || p != end || counts.size() < required) engine::fail("bake cameras: \"" + spec + "\" is not " + form);
    return counts;
}

// The value below which `share` of the values lie (linear between order statistics).
float quantile(std::vector<float>& values, float share) {
    const float position = share * static_cast<float>(values.size() - 1);
    const auto lower = static_cast<std::size_t>(position);
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(lower), values.end());
    const float low = values[lower];
    if (lower + 1 >= values.size()) return low;
    const float high = *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(lower) + 1, values.end());
    return low + (position - static_cast<float>(lower)) * (high - low);
}

eval::CameraPose make_pose(const std::string& name, const glm::vec3& eye, const glm::vec3& forward, const glm::vec3& up,
                           float focus) {
    eval::CameraPose pose;
    pose.name = name;
    pose.eye = eye;
    pose.forward = forward;  // unit (the callers' directions, left unrounded)
    pose.up = glm::normalize(glm::cross(glm::cross(pose.forward, up), pose.forward));
    pose.fov_y = glm::radians(50.0f);
    pose.focus_distance = focus;
    return pose;
}

glm::vec3 unit_up(const glm::vec3& up) {
    if (!(glm::length(up) > 0.0f)) engine::fail("bake cameras: the up direction must not be zero");
    return glm::normalize(up);
}

std::vector<eval::CameraPose> ring_poses(int rings, int per_ring, const CameraPlacement& placement) {
    const glm::vec3 u = unit_up(placement.up);
    const glm::vec3 a = glm::normalize(glm::cross(u, std::abs(u.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1)));
    const glm::vec3 b = glm::cross(u, a);
    const float distance = 2.2f * placement.extent.radius;
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
            poses.push_back(make_pose("bake ring " + std::to_string(r) + " view " + std::to_string(j),
                                      placement.extent.centre + dir * distance, -dir, u, distance));
        }
    }
    return poses;
}

// The scene in the grid's frame: percentiles of the Gaussians' offsets from the centre along right,
// up and forward (or the extent's sphere when there are no positions).
struct GridBox {
    float across_lo, across_hi, up_lo, up_hi, near, far;
};

GridBox grid_box(const CameraPlacement& placement, const glm::vec3& right, const glm::vec3& up, const glm::vec3& f) {
    const float r = placement.extent.radius;
    if (placement.positions.empty()) return {-r, r, -r, r, -r, r};
    std::vector<float> across, upward, along;
    across.reserve(placement.positions.size());
    upward.reserve(placement.positions.size());
    along.reserve(placement.positions.size());
    for (const glm::vec3& p : placement.positions) {
        const glm::vec3 d = p - placement.extent.centre;
        across.push_back(glm::dot(d, right));
        upward.push_back(glm::dot(d, up));
        along.push_back(glm::dot(d, f));
    }
    return {quantile(across, 0.05f), quantile(across, 0.95f), quantile(upward, 0.05f),
            quantile(upward, 0.95f), quantile(along, 0.02f),  quantile(along, 0.98f)};
}

std::vector<eval::CameraPose> grid_poses(int columns, int rows, int layers, const CameraPlacement& placement) {
    const glm::vec3 u0 = unit_up(placement.up);
    const glm::vec3 forward = glm::length(placement.forward) > 0.0f ? placement.forward : default_forward(u0);
    const glm::vec3 f = glm::normalize(forward);
    const glm::vec3 cross = glm::cross(f, u0);
    if (!(glm::length(cross) > 1e-3f)) engine::fail("bake cameras: grid: the forward direction is parallel to up");
    const glm::vec3 right = glm::normalize(cross), up = glm::cross(right, f);
    const GridBox box = grid_box(placement, right, up, f);
    const float depth = std::max(box.far - box.near, 1e-3f * placement.extent.radius);
    const float mid_a = 0.5f * (box.across_lo + box.across_hi), half_a = 0.25f * (box.across_hi - box.across_lo);
    const float mid_u = 0.5f * (box.up_lo + box.up_hi), half_u = 0.25f * (box.up_hi - box.up_lo);
    std::vector<eval::CameraPose> poses;
    for (int d = 0; d < layers; ++d)
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < columns; ++c) {
                const float sx = columns == 1 ? 0.0f : -1.0f + 2.0f * static_cast<float>(c) / (columns - 1.0f);
                const float sy = rows == 1 ? 0.0f : -1.0f + 2.0f * static_cast<float>(r) / (rows - 1.0f);
                const glm::vec3 eye = placement.extent.centre + right * (mid_a + sx * half_a) +
                                      up * (mid_u + sy * half_u) + f * (box.near + 0.12f * d * depth);
                const float yaw = glm::radians(kGridYawDeg) * sx, pitch = glm::radians(kGridPitchDeg) * sy;
                const glm::vec3 dir =
                    std::cos(pitch) * (std::cos(yaw) * f + std::sin(yaw) * right) + std::sin(pitch) * up;
                poses.push_back(
                    make_pose("bake grid " + std::to_string(d) + " " + std::to_string(r) + "," + std::to_string(c), eye,
                              glm::normalize(dir), up, 0.5f * depth));
            }
    return poses;
}

std::vector<eval::CameraPose> inside_poses(int rings, int per_ring, const CameraPlacement& placement) {
    const glm::vec3 u = unit_up(placement.up);
    const glm::vec3 a = glm::normalize(glm::cross(u, std::abs(u.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1)));
    const glm::vec3 b = glm::cross(u, a);
    const float radius = placement.extent.radius;
    std::vector<eval::CameraPose> poses;
    for (int r = 0; r < rings; ++r)
        for (int j = 0; j < per_ring; ++j) {
            const float azimuth =
                2.0f * kPi * (static_cast<float>(j) + 0.5f * static_cast<float>(r % 2)) / static_cast<float>(per_ring);
            const glm::vec3 out = std::cos(azimuth) * a + std::sin(azimuth) * b;
            const glm::vec3 eye = placement.extent.centre +
                                  out * (0.6f * radius * (static_cast<float>(r) + 0.5f) / static_cast<float>(rings)) +
                                  u * (0.05f * radius);
            poses.push_back(make_pose("bake inside " + std::to_string(r) + " view " + std::to_string(j), eye,
                                      glm::normalize(std::cos(0.1f) * out - std::sin(0.1f) * u), u, 0.5f * radius));
        }
    return poses;
}

}  // namespace

glm::vec3 default_forward(const glm::vec3& up) {
    const glm::vec3 f = glm::cross(unit_up(up), glm::vec3(1.0f, 0.0f, 0.0f));
    if (!(glm::length(f) > 1e-3f))
        engine::fail("bake cameras: up is along X; give the forward direction (--forward X,Y,Z)");
    return glm::normalize(f);
}

std::vector<eval::CameraPose> bake_camera_poses(const std::string& spec, const CameraPlacement& placement) {
    if (spec == "auto") return ring_poses(3, 8, placement);
    if (const auto rings = parse_counts(spec, "rings:", {64, 256}, 2, "rings:RxA with R in 1..64 and A in 1..256"))
        return ring_poses((*rings)[0], (*rings)[1], placement);
    if (const auto grid =
            parse_counts(spec, "grid:", {64, 64, 8}, 2, "grid:CxR or grid:CxRxD with C and R in 1..64 and D in 1..8"))
        return grid_poses((*grid)[0], (*grid)[1], grid->size() > 2 ? (*grid)[2] : 2, placement);
    if (const auto inside = parse_counts(spec, "inside:", {16, 64}, 2, "inside:RxA with R in 1..16 and A in 1..64"))
        return inside_poses((*inside)[0], (*inside)[1], placement);
    return eval::load_camera_set(spec, placement.extent, placement.up);
}

std::vector<eval::CameraPose> bake_camera_poses(const std::string& spec, const eval::SceneExtent& extent,
                                                const glm::vec3& up) {
    CameraPlacement placement;
    placement.extent = extent;
    placement.up = up;
    return bake_camera_poses(spec, placement);
}

std::string auto_camera_spec(CaptureShape shape) {
    switch (shape) {
        case CaptureShape::forward:
            return "grid:8x6x3";
        case CaptureShape::world:
            return "inside:2x8";
        default:
            return "rings:3x8";
    }
}

std::optional<CaptureShape> generated_capture_shape(const std::string& spec) {
    if (spec.rfind("rings:", 0) == 0 || spec.rfind("orbit:", 0) == 0) return CaptureShape::orbit;
    if (spec.rfind("grid:", 0) == 0) return CaptureShape::forward;
    if (spec.rfind("inside:", 0) == 0) return CaptureShape::world;
    return std::nullopt;
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
