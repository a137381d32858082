#include "splat_lod/core/camera_set.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"

namespace splat_lod::eval {
namespace {

using nlohmann::json;

[[noreturn]] void camera_error(const std::filesystem::path& path, std::size_t index, const std::string& problem) {
    engine::fail(path.string() + ": camera " + std::to_string(index) + ": " + problem);
}

json parse_camera_array(const std::string& text, const std::filesystem::path& path) {
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {  // parse_error, and out_of_range for numbers beyond double
        engine::fail(path.string() + ": not valid JSON: " + e.what());
    }
    if (!doc.is_array()) engine::fail(path.string() + ": expected a JSON array of cameras");
    if (doc.empty()) engine::fail(path.string() + ": the camera list is empty");
    return doc;
}

double number(const json& value, const std::filesystem::path& path, std::size_t index, const std::string& key) {
    if (!value.is_number()) camera_error(path, index, "\"" + key + "\" must be a number");
    const double v = value.get<double>();
    if (!std::isfinite(v)) camera_error(path, index, "\"" + key + "\" is not finite");
    if (std::abs(v) > std::numeric_limits<float>::max())
        camera_error(path, index, "\"" + key + "\" is beyond float range");
    return v;
}

glm::vec3 vec3_field(const json& camera, const std::string& key, const std::filesystem::path& path, std::size_t index) {
    if (!camera.contains(key)) camera_error(path, index, "missing \"" + key + "\"");
    const json& v = camera[key];
    if (!v.is_array() || v.size() != 3) camera_error(path, index, "\"" + key + "\" must be an array of 3 numbers");
    return {static_cast<float>(number(v[0], path, index, key)), static_cast<float>(number(v[1], path, index, key)),
            static_cast<float>(number(v[2], path, index, key))};
}

double positive_field(const json& camera, const std::string& key, const std::filesystem::path& path,
                      std::size_t index) {
    if (!camera.contains(key)) camera_error(path, index, "missing \"" + key + "\"");
    const double v = number(camera[key], path, index, key);
    if (v <= 0.0) camera_error(path, index, "\"" + key + "\" must be positive");
    return v;
}

// Rows of the camera-to-world rotation; its columns are the camera's x, y, z axes in the world.
glm::mat3 rotation_field(const json& camera, const std::filesystem::path& path, std::size_t index) {
    const json& r = camera.contains("rotation") ? camera["rotation"] : json();
    if (!r.is_array() || r.size() != 3) camera_error(path, index, "\"rotation\" must be a 3x3 array");
    glm::mat3 m;
    for (int row = 0; row < 3; ++row) {
        const json& values = r[static_cast<std::size_t>(row)];
        if (!values.is_array() || values.size() != 3) camera_error(path, index, "\"rotation\" must be a 3x3 array");
        for (int col = 0; col < 3; ++col)
            m[col][row] = static_cast<float>(number(values[static_cast<std::size_t>(col)], path, index, "rotation"));
    }
    // det = 1 alone admits shears: a rotation's columns are also orthonormal (mᵀm = I).
    const glm::mat3 gram = glm::transpose(m) * m;
    bool orthonormal = true;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) orthonormal = orthonormal && std::abs(gram[i][j] - (i == j ? 1.0f : 0.0f)) <= 1e-2f;
    if (!orthonormal || std::abs(glm::determinant(m) - 1.0f) > 1e-2f)
        camera_error(path, index, "\"rotation\" is not a rotation matrix");
    return m;
}

CameraPose inria_camera(const json& camera, const std::filesystem::path& path, std::size_t index) {
    if (!camera.is_object()) camera_error(path, index, "expected an object");
    const glm::mat3 rotation = rotation_field(camera, path, index);
    const double height = positive_field(camera, "height", path, index);
    positive_field(camera, "width", path, index);
    positive_field(camera, "fx", path, index);
    const double fy = positive_field(camera, "fy", path, index);
    CameraPose pose;
    if (camera.contains("img_name") && !camera["img_name"].is_string())
        camera_error(path, index, "\"img_name\" must be a string");
    pose.name = camera.value("img_name", "camera " + std::to_string(index));
    pose.eye = vec3_field(camera, "position", path, index);
    // OpenCV camera axes (x right, y down, z forward) to the engine's (x right, y up, −z forward).
    pose.forward = glm::normalize(rotation[2]);
    // Made exactly orthogonal to forward: the file's matrix is orthonormal only to its precision.
    pose.up = glm::normalize(-rotation[1] + glm::dot(rotation[1], pose.forward) * pose.forward);
    pose.fov_y = static_cast<float>(2.0 * std::atan(height / (2.0 * fy)));
    if (!(pose.fov_y < glm::radians(179.0f)))
        camera_error(path, index, "\"height\" / \"fy\" give a field of view of 179 degrees or more");
    return pose;
}

CameraPose path_camera(const json& camera, const std::filesystem::path& path, std::size_t index) {
    if (!camera.is_object()) camera_error(path, index, "expected an object");
    const glm::vec3 eye = vec3_field(camera, "eye", path, index), target = vec3_field(camera, "target", path, index);
    const glm::vec3 up = camera.contains("up") ? vec3_field(camera, "up", path, index) : glm::vec3(0, 1, 0);
    const double fov = camera.contains("fov_y_deg") ? number(camera["fov_y_deg"], path, index, "fov_y_deg") : 50.0;
    if (fov <= 0.0 || fov >= 180.0) camera_error(path, index, "\"fov_y_deg\" must be in (0, 180)");
    const float distance = glm::length(target - eye);
    if (!(distance > 0.0f)) camera_error(path, index, "\"eye\" and \"target\" coincide");
    if (!std::isfinite(distance)) camera_error(path, index, "\"eye\" and \"target\" are too far apart");
    CameraPose pose;
    pose.name = camera.contains("name") && camera["name"].is_string() ? camera["name"].get<std::string>()
                                                                      : "camera " + std::to_string(index);
    pose.eye = eye;
    pose.forward = (target - eye) / distance;
    // `up` scaled to its largest component first, so that large values cannot overflow the product.
    const float up_scale = std::max({std::abs(up.x), std::abs(up.y), std::abs(up.z)});
    const glm::vec3 right = up_scale > 0.0f ? glm::cross(pose.forward, up / up_scale) : glm::vec3(0.0f);
    if (glm::length(right) < 1e-6f) camera_error(path, index, "\"up\" is parallel to the view direction");
    pose.up = glm::normalize(glm::cross(glm::normalize(right), pose.forward));
    pose.fov_y = glm::radians(static_cast<float>(fov));
    pose.focus_distance = distance;
    return pose;
}

// INRIA cameras carry no target: focus on the scene centre's projection on the view ray (or the
// centre's distance when it lies behind the camera).
void focus_on(CameraPose& pose, const SceneExtent& extent) {
    const float along = glm::dot(extent.centre - pose.eye, pose.forward);
    pose.focus_distance = along > 1e-4f ? along : std::max(glm::length(extent.centre - pose.eye), 1e-3f);
}

}  // namespace

CameraPose dolly(const CameraPose& pose, float factor) {
    CameraPose out = pose;
    out.eye = pose.target() - pose.forward * pose.focus_distance * factor;
    out.focus_distance = pose.focus_distance * factor;
    return out;
}

engine::CameraView make_view(const CameraPose& pose, int width, int height) {
    // Near/far relative to the focus distance keep depth precision the same at every dolly factor.
    return engine::make_look_at_camera(pose.eye, pose.target(), pose.up, pose.fov_y, width, height,
                                       0.01f * pose.focus_distance, 1000.0f * pose.focus_distance);
}

std::vector<CameraPose> parse_inria_cameras(const std::string& text, const std::string& name) {
    const std::filesystem::path path(name);
    const json doc = parse_camera_array(text, path);
    std::vector<CameraPose> poses;
    for (std::size_t i = 0; i < doc.size(); ++i) poses.push_back(inria_camera(doc[i], path, i));
    return poses;
}

std::vector<CameraPose> parse_camera_path(const std::string& text, const std::string& name) {
    const std::filesystem::path path(name);
    const json doc = parse_camera_array(text, path);
    std::vector<CameraPose> poses;
    for (std::size_t i = 0; i < doc.size(); ++i) poses.push_back(path_camera(doc[i], path, i));
    return poses;
}

std::vector<CameraPose> read_inria_cameras(const std::filesystem::path& path) {
    return parse_inria_cameras(engine::read_text_file(path), path.string());
}

std::vector<CameraPose> read_camera_path(const std::filesystem::path& path) {
    return parse_camera_path(engine::read_text_file(path), path.string());
}

SceneExtent robust_extent(const std::vector<glm::vec3>& points) {
    if (points.empty()) engine::fail("splat_lod::eval::robust_extent(): the scene has no Gaussians");
    SceneExtent extent;
    std::vector<float> v(points.size());
    for (int axis = 0; axis < 3; ++axis) {
        for (std::size_t i = 0; i < points.size(); ++i) v[i] = points[i][axis];
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        extent.centre[axis] = v[v.size() / 2];
    }
    for (std::size_t i = 0; i < points.size(); ++i) v[i] = glm::length(points[i] - extent.centre);
    const std::size_t p90 = v.size() * 9 / 10;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(p90), v.end());
    extent.radius = std::max(v[p90], 1e-4f);
    return extent;
}

std::vector<CameraPose> orbit_poses(const SceneExtent& extent, const glm::vec3& up, int count, float distance_factor) {
    if (count < 1)
        engine::fail("splat_lod::eval::orbit_poses(): need at least one camera, got " + std::to_string(count));
    const glm::vec3 u = glm::normalize(up);
    const glm::vec3 a = glm::normalize(glm::cross(u, std::abs(u.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1)));
    const glm::vec3 b = glm::cross(u, a);
    std::vector<CameraPose> poses;
    for (int i = 0; i < count; ++i) {
        const float azimuth = 0.6f + 2.0f * 3.14159265f * static_cast<float>(i) / static_cast<float>(count);
        const float elevation = (i % 2 == 0) ? 0.25f : -0.1f;
        const glm::vec3 dir =
            std::cos(elevation) * (std::cos(azimuth) * a + std::sin(azimuth) * b) + std::sin(elevation) * u;
        CameraPose pose;
        pose.name = "orbit " + std::to_string(i);
        pose.eye = extent.centre + dir * extent.radius * distance_factor;
        pose.forward = -dir;
        pose.up = glm::normalize(glm::cross(glm::cross(pose.forward, u), pose.forward));
        pose.fov_y = glm::radians(50.0f);
        pose.focus_distance = extent.radius * distance_factor;
        poses.push_back(pose);
    }
    return poses;
}

std::vector<CameraPose> load_camera_set(const std::string& spec, const SceneExtent& extent, const glm::vec3& up) {
    if (spec.rfind("orbit:", 0) == 0) {
        const std::string n = spec.substr(6);
        int count = 0;
        try {
            std::size_t used = 0;
            count = std::stoi(n, &used);
            if (used != n.size()) count = 0;
        } catch (const std::exception&) {
            count = 0;
        }
        if (count < 1 || count > 1000) engine::fail("--cameras " + spec + ": expected orbit:N with N in 1..1000");
        return orbit_poses(extent, up, count);
    }
    const std::string text = engine::read_text_file(spec);
    const json doc = parse_camera_array(text, spec);
    const bool inria = doc[0].is_object() && doc[0].contains("rotation");
    auto poses = inria ? parse_inria_cameras(text, spec) : parse_camera_path(text, spec);
    if (inria)
        for (auto& pose : poses) focus_on(pose, extent);
    return poses;
}

}  // namespace splat_lod::eval
