// Training cameras from INRIA cameras.json or COLMAP's text model (training_cameras.h).
#include "splat_lod/core/training_cameras.h"

#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"

namespace splat_lod::eval {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void line_error(const std::string& name, std::size_t line, const std::string& problem) {
    engine::fail(name + ": line " + std::to_string(line) + ": " + problem);
}

// The text's lines with their 1-based numbers, comments dropped (blank lines kept: an image's points
// line may be empty).
std::vector<std::pair<std::size_t, std::string>> lines_of(const std::string& text) {
    std::vector<std::pair<std::size_t, std::string>> lines;
    std::istringstream in(text);
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.rfind('#', 0) != 0) lines.emplace_back(number, line);
    }
    return lines;
}

std::vector<std::string> tokens_of(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> tokens;
    for (std::string token; in >> token;) tokens.push_back(token);
    return tokens;
}

double number_of(const std::string& token, const std::string& name, std::size_t line) {
    try {
        std::size_t used = 0;
        const double v = std::stod(token, &used);
        if (used == token.size() && std::isfinite(v)) return v;
    } catch (const std::exception&) {
    }
    line_error(name, line, "\"" + token + "\" is not a finite number");
}

// Whether a line is an image's 2D points (empty, or numbers only: X Y POINT3D_ID triples), not the next
// image (whose NAME is not a number): a file written without points lines loses no image.
bool points_line(const std::string& line) {
    for (const std::string& token : tokens_of(line)) {
        char* end = nullptr;
        std::strtod(token.c_str(), &end);
        if (end != token.c_str() + token.size()) return false;
    }
    return true;
}

// CAMERA_ID → vertical field of view (radians).
std::map<std::string, float> camera_fovs(const std::string& text, const std::string& name) {
    static const std::map<std::string, int> focal_y = {{"SIMPLE_PINHOLE", 0},
                                                       {"SIMPLE_RADIAL", 0},
                                                       {"RADIAL", 0},
                                                       {"SIMPLE_RADIAL_FISHEYE", 0},
                                                       {"RADIAL_FISHEYE", 0},
                                                       {"PINHOLE", 1},
                                                       {"OPENCV", 1},
                                                       {"OPENCV_FISHEYE", 1},
                                                       {"FULL_OPENCV", 1},
                                                       {"FOV", 1},
                                                       {"THIN_PRISM_FISHEYE", 1}};
    std::map<std::string, float> fovs;
    for (const auto& [line, content] : lines_of(text)) {
        const auto t = tokens_of(content);
        if (t.empty()) continue;
        if (t.size() < 5) line_error(name, line, "expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS...");
        const auto model = focal_y.find(t[1]);
        if (model == focal_y.end()) line_error(name, line, "unknown camera model \"" + t[1] + "\"");
        const std::size_t f = 4 + static_cast<std::size_t>(model->second);
        if (t.size() <= f) line_error(name, line, "too few parameters for " + t[1]);
        const double height = number_of(t[3], name, line), fy = number_of(t[f], name, line);
        if (!(height > 0.0 && fy > 0.0)) line_error(name, line, "the height and focal length must be positive");
        const double fov = 2.0 * std::atan(height / (2.0 * fy));
        if (!(fov < glm::radians(179.0))) line_error(name, line, "a field of view of 179 degrees or more");
        fovs[t[0]] = static_cast<float>(fov);
    }
    return fovs;
}

CameraPose colmap_pose(const std::vector<std::string>& t, const std::map<std::string, float>& fovs,
                       const std::string& name, std::size_t line) {
    double v[7];
    for (int i = 0; i < 7; ++i) v[i] = number_of(t[static_cast<std::size_t>(i) + 1], name, line);
    const glm::dquat q(v[0], v[1], v[2], v[3]);
    const double norm = glm::length(q);
    if (!(norm > 1e-6)) line_error(name, line, "the quaternion is zero");
    if (!std::isfinite(norm)) line_error(name, line, "the quaternion's length is beyond double range");
    const glm::dmat3 world_to_camera = glm::mat3_cast(q / norm);
    const glm::dmat3 camera_to_world = glm::transpose(world_to_camera);
    const auto fov = fovs.find(t[8]);
    if (fov == fovs.end()) line_error(name, line, "camera " + t[8] + " is not in cameras.txt");
    CameraPose pose;
    pose.name = t[9];
    pose.eye = glm::vec3(-(camera_to_world * glm::dvec3(v[4], v[5], v[6])));
    pose.forward = glm::normalize(glm::vec3(camera_to_world[2]));
    pose.up = glm::normalize(-glm::vec3(camera_to_world[1]));
    pose.fov_y = fov->second;
    if (!std::isfinite(glm::length(pose.eye))) line_error(name, line, "the camera's centre is not finite");
    return pose;
}

}  // namespace

std::vector<CameraPose> parse_colmap_cameras(const std::string& images, const std::string& cameras,
                                             const std::string& images_name, const std::string& cameras_name) {
    const auto fovs = camera_fovs(cameras, cameras_name);
    const auto lines = lines_of(images);
    std::vector<CameraPose> poses;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const auto t = tokens_of(lines[i].second);
        if (t.empty()) continue;
        if (t.size() < 10)
            line_error(images_name, lines[i].first, "expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
        poses.push_back(colmap_pose(t, fovs, images_name, lines[i].first));
        if (i + 1 < lines.size() && points_line(lines[i + 1].second)) ++i;  // its points (may be empty)
    }
    if (poses.empty()) engine::fail(images_name + ": no image in the file");
    return poses;
}

std::vector<fs::path> training_camera_files(const fs::path& path) {
    std::error_code ec;
    fs::path file = path;
    if (fs::is_directory(path, ec)) {
        for (const char* name : {"cameras.json", "images.txt", "sparse/0/images.txt"})
            if (fs::is_regular_file(path / name, ec)) {
                file = path / name;
                break;
            }
        if (file == path) engine::fail(path.string() + ": holds no cameras.json or COLMAP images.txt");
    }
    if (file.filename() == "images.txt") return {file, file.parent_path() / "cameras.txt"};
    return {file};
}

std::vector<CameraPose> read_training_cameras(const fs::path& path) {
    const std::vector<fs::path> files = training_camera_files(path);
    if (files.size() == 1) return read_inria_cameras(files[0]);
    std::error_code ec;
    if (!fs::is_regular_file(files[1], ec))
        engine::fail(files[0].string() + ": its cameras.txt (the fields of view) is missing beside it");
    return parse_colmap_cameras(engine::read_text_file(files[0]), engine::read_text_file(files[1]), files[0].string(),
                                files[1].string());
}

}  // namespace splat_lod::eval
