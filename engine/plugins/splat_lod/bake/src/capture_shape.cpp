// Detection of the capture shape from a camera set (capture_shape.h).
#include "splat_lod/bake/capture_shape.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/core/error.h"

namespace splat_lod::bake {
namespace {

constexpr float kDegrees = 57.2957795f;

float angle_deg(const glm::vec3& a, const glm::vec3& b) {
    return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f)) * kDegrees;
}

// The value below which `share` of the values lie (the largest for share 1).
float quantile(std::vector<float> values, float share) {
    if (values.empty()) return 0.0f;
    std::sort(values.begin(), values.end());
    const auto rank = static_cast<std::size_t>(std::ceil(share * static_cast<float>(values.size())));
    return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

void measure(const std::vector<eval::CameraPose>& cameras, const eval::SceneExtent& extent, CaptureDetection& d) {
    glm::vec3 sum(0.0f);
    for (const auto& c : cameras) sum += glm::normalize(c.forward);
    const float length = glm::length(sum);
    d.mean_direction = length > 1e-3f * static_cast<float>(cameras.size()) ? sum / length : glm::vec3(0, 0, -1);
    std::vector<float> cone, towards;
    std::size_t behind = 0, inside = 0;
    for (const auto& c : cameras) {
        const glm::vec3 f = glm::normalize(c.forward);
        cone.push_back(angle_deg(f, d.mean_direction));
        const glm::vec3 to_centre = extent.centre - c.eye;
        const float distance = glm::length(to_centre);
        // A camera on the centre looks at nothing in particular: 90°.
        towards.push_back(distance > 1e-4f * extent.radius ? angle_deg(f, to_centre / distance) : 90.0f);
        behind += glm::dot(c.eye - extent.centre, d.mean_direction) < 0.0f;
        inside += distance < extent.radius;
    }
    const float n = static_cast<float>(cameras.size());
    d.cone_deg = quantile(cone, cameras.size() < 20 ? 1.0f : 0.95f);
    d.towards_centre_deg = quantile(towards, 0.5f);
    d.one_side_fraction = static_cast<float>(behind) / n;
    d.inside_fraction = static_cast<float>(inside) / n;
}

}  // namespace

const char* capture_shape_name(CaptureShape shape) {
    switch (shape) {
        case CaptureShape::forward:
            return "forward";
        case CaptureShape::world:
            return "world";
        default:
            return "orbit";
    }
}

std::optional<CaptureShape> parse_capture_shape(const std::string& text, const std::string& option) {
    if (text == "auto") return std::nullopt;
    if (text == "orbit") return CaptureShape::orbit;
    if (text == "forward") return CaptureShape::forward;
    if (text == "world") return CaptureShape::world;
    engine::fail(option + ": expected auto, orbit, forward or world, got \"" + text + "\"");
}

CaptureDetection detect_capture_shape(const std::vector<eval::CameraPose>& cameras, const eval::SceneExtent& extent) {
    CaptureDetection d;
    if (cameras.empty()) {
        d.reason = "orbit: no cameras";
        return d;
    }
    measure(cameras, extent, d);
    char numbers[256];
    std::snprintf(numbers, sizeof numbers,
                  "view directions within %.0f deg of their mean, %.0f%% of the cameras behind the centre, median "
                  "%.0f deg from looking at the centre, %.0f%% inside the robust radius",
                  static_cast<double>(d.cone_deg), 100.0 * static_cast<double>(d.one_side_fraction),
                  static_cast<double>(d.towards_centre_deg), 100.0 * static_cast<double>(d.inside_fraction));
    if (d.cone_deg < kForwardConeDeg && d.one_side_fraction >= kForwardOneSide) {
        d.shape = CaptureShape::forward;
        d.reason = std::string("forward: ") + numbers;
    } else if (d.towards_centre_deg < kOrbitTowardsCentreDeg) {
        d.shape = CaptureShape::orbit;
        d.reason = std::string("orbit: ") + numbers;
    } else if (d.inside_fraction >= kWorldInside) {
        d.shape = CaptureShape::world;
        d.reason = std::string("world: ") + numbers;
    } else {
        d.shape = CaptureShape::orbit;
        d.reason = std::string("orbit (no rule matched): ") + numbers;
    }
    return d;
}

BakeOptions capture_defaults(BakeOptions options, CaptureShape shape) {
    if (shape != CaptureShape::forward) return options;
    options.pooling = PoolingRule::moments;
    options.cells = CellRule::adaptive;
    options.choose_recipe = false;
    options.min_axis_ratio = 0.3;
    options.member_ranges = true;
    options.refine_cameras = 0;  // all of them
    return options;
}

namespace {

// The 1st–99th percentile extent of the centres along each axis (every 16th centre).
glm::dvec3 robust_extent(const SplatCloud& cloud) {
    glm::dvec3 extent(0.0);
    for (int k = 0; k < 3; ++k) {
        std::vector<float> values;
        for (std::size_t i = 0; i < cloud.size(); i += 16) values.push_back(cloud.positions[i][k]);
        std::sort(values.begin(), values.end());
        if (!values.empty()) extent[k] = values[values.size() * 99 / 100] - values[values.size() / 100];
    }
    return extent;
}

}  // namespace

std::string streamed_world_advice(const SplatCloud& cloud) {
    char text[256];
    if (cloud.size() >= kWorldCaptureGaussians) {
        std::snprintf(text, sizeof text, "%zu Gaussians (one LOD file serves captures of %llu or more badly)",
                      cloud.size(), static_cast<unsigned long long>(kWorldCaptureGaussians));
        return text;
    }
    const glm::dvec3 e = robust_extent(cloud);
    const double thinnest = std::min({e.x, e.y, e.z}), widest = std::max({e.x, e.y, e.z});
    if (cloud.size() >= kFlatCaptureGaussians && thinnest > 0.0 && widest >= kFlatCaptureRatio * thinnest) {
        std::snprintf(text, sizeof text,
                      "a flat capture of %zu Gaussians, %.0f times wider than it is thin (an aerial capture)",
                      cloud.size(), widest / thinnest);
        return text;
    }
    return "";
}

}  // namespace splat_lod::bake
