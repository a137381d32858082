// The temporal sweep's paths, its supersampling factor, its pair error and the checks of its
// options (splat_lod/eval/temporal_sweep.h); no GL.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.h"
#include "splat_lod/eval/temporal_sweep.h"

namespace splat_lod::eval {
namespace {

void check_same_sizes(const FloatImage& a, const FloatImage& b, const FloatImage& c, const FloatImage& d) {
    for (const FloatImage* image : {&b, &c, &d})
        if (image->width != a.width || image->height != a.height)
            engine::fail("splat_lod::eval::temporal_pair_error(): image sizes differ: " + std::to_string(a.width) +
                         "x" + std::to_string(a.height) + " vs " + std::to_string(image->width) + "x" +
                         std::to_string(image->height));
}

// `start` dollied by each factor, named "<name> <i> (<factor>x)" with `digits` decimals.
std::vector<CameraPose> dollied(const CameraPose& start, const std::vector<double>& factors, const std::string& name,
                                int digits) {
    std::vector<CameraPose> poses;
    for (std::size_t i = 0; i < factors.size(); ++i) {
        CameraPose pose = dolly(start, static_cast<float>(factors[i]));
        char label[96];
        std::snprintf(label, sizeof label, "%s %zu (%.*fx)", name.c_str(), i, digits, factors[i]);
        pose.name = label;
        poses.push_back(pose);
    }
    return poses;
}

// Throws naming `option` when a name repeats.
void fail_if_repeated(const std::vector<std::string>& names, const std::string& option) {
    for (std::size_t i = 0; i < names.size(); ++i)
        if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(i), names[i]) !=
            names.begin() + static_cast<std::ptrdiff_t>(i))
            engine::fail(option + ": \"" + names[i] + "\" is listed twice");
}

std::string size_text(int width, int height) {
    return std::to_string(width) + "\u00d7" + std::to_string(height);
}

}  // namespace

int temporal_supersampling(int width, int height, int max_reference_side) {
    for (int s = kMaxTemporalSupersampling; s >= 1; --s)
        if (static_cast<long long>(s) * width <= max_reference_side &&
            static_cast<long long>(s) * height <= max_reference_side)
            return s;
    return 0;
}

double temporal_pair_error(const FloatImage& method_previous, const FloatImage& method,
                           const FloatImage& reference_previous, const FloatImage& reference) {
    check_same_sizes(method_previous, method, reference_previous, reference);
    if (method.rgb.empty()) return 0.0;
    double sum = 0.0;
    for (std::size_t i = 0; i < method.rgb.size(); ++i)
        sum += std::abs(static_cast<double>(method.rgb[i]) - method_previous.rgb[i] -
                        (static_cast<double>(reference.rgb[i]) - reference_previous.rgb[i]));
    return 255.0 * sum / static_cast<double>(method.rgb.size());
}

double temporal_pair_pop(const FloatImage& method_previous, const FloatImage& method,
                         const FloatImage& reference_previous, const FloatImage& reference) {
    check_same_sizes(method_previous, method, reference_previous, reference);
    if (method.rgb.empty()) return 0.0;
    std::vector<double> pixels(method.rgb.size() / 3);
    for (std::size_t p = 0; p < pixels.size(); ++p) {
        double sum = 0.0;
        for (std::size_t c = 3 * p; c < 3 * p + 3; ++c)
            sum += std::abs(static_cast<double>(method.rgb[c]) - method_previous.rgb[c] -
                            (static_cast<double>(reference.rgb[c]) - reference_previous.rgb[c]));
        pixels[p] = 255.0 * sum / 3.0;
    }
    // Nearest rank: the ⌈q·n⌉-th smallest value.
    const auto rank = static_cast<std::size_t>(std::ceil(kPopPercentile * static_cast<double>(pixels.size())));
    const auto nth = pixels.begin() + static_cast<std::ptrdiff_t>(std::clamp<std::size_t>(rank, 1, pixels.size()) - 1);
    std::nth_element(pixels.begin(), nth, pixels.end());
    return *nth;
}

double selection_switch_pop(const FloatImage& frozen, const FloatImage& image) {
    // |(M_t − frozen) − (R − R)|: the pair pop with a reference that does not change.
    return temporal_pair_pop(frozen, image, image, image);
}

engine::CameraView with_selection_of(const engine::CameraView& view, const engine::CameraView& previous) {
    engine::CameraView frozen = view;
    frozen.selection_view = previous.view;
    return frozen;
}

engine::Image temporal_difference_image(const FloatImage& method_previous, const FloatImage& method,
                                        const FloatImage& reference_previous, const FloatImage& reference, float gain) {
    check_same_sizes(method_previous, method, reference_previous, reference);
    FloatImage grey = make_float_image(method.width, method.height);
    for (std::size_t p = 0; p < grey.rgb.size(); p += 3) {
        float sum = 0.0f;
        for (std::size_t c = p; c < p + 3; ++c)
            sum += std::abs(method.rgb[c] - method_previous.rgb[c] - (reference.rgb[c] - reference_previous.rgb[c]));
        std::fill_n(grey.rgb.begin() + static_cast<std::ptrdiff_t>(p), 3, std::min(1.0f, gain * sum / 3.0f));
    }
    return to_rgba8(grey);
}

std::vector<double> temporal_pair_errors(const std::vector<FloatImage>& method,
                                         const std::vector<FloatImage>& reference) {
    if (method.size() != reference.size())
        engine::fail("splat_lod::eval::temporal_pair_errors(): " + std::to_string(method.size()) +
                     " method frames against " + std::to_string(reference.size()) + " reference frames");
    std::vector<double> errors;
    for (std::size_t t = 1; t < method.size(); ++t)
        errors.push_back(temporal_pair_error(method[t - 1], method[t], reference[t - 1], reference[t]));
    return errors;
}

std::vector<CameraPose> dolly_path(const CameraPose& start, int frames) {
    if (frames < kMinTemporalFrames)
        engine::fail("--temporal-frames: " + std::to_string(frames) + " frames are too few (at least " +
                     std::to_string(kMinTemporalFrames) + ")");
    const int out = (frames + 1) / 2, back = frames - out;
    std::vector<double> factors;
    for (int i = 0; i < frames; ++i) {
        const double exponent = i < out ? static_cast<double>(i) / (out - 1)
                                        : 1.0 - static_cast<double>(i - out + 1) / static_cast<double>(back);
        factors.push_back(std::pow(static_cast<double>(kDollyMaxFactor), exponent));
    }
    return dollied(start, factors, "dolly", 2);
}

std::vector<CameraPose> stride_path(const CameraPose& start, double speed, double metres_per_unit,
                                    const std::string& name) {
    if (!(speed > 0.0) || !(metres_per_unit > 0.0) || !std::isfinite(metres_per_unit))
        engine::fail("splat_lod::eval::stride_path(): the speed and the scene's scale must be > 0");
    const double distance = start.focus_distance;
    const double step = speed / kPathFramesPerSecond / metres_per_unit;  // scene units a frame
    const double wanted = std::ceil((kStrideMaxFactor - 1.0) * distance / step);
    const int steps = std::max(kMinTemporalFrames - 1, static_cast<int>(std::min<double>(wanted, kMaxStrideFrames)));
    std::vector<double> factors;
    for (int i = 0; i <= steps; ++i) factors.push_back(1.0 + i * step / distance);
    return dollied(start, factors, name, 3);
}

std::vector<CameraPose> slow_dolly_path(const CameraPose& start) {
    const int steps = static_cast<int>(std::lround(std::log2(kSlowDollyMaxFactor) * kSlowDollyStepsPerOctave));
    std::vector<double> factors;
    for (int i = 0; i <= steps; ++i) factors.push_back(std::exp2(static_cast<double>(i) / kSlowDollyStepsPerOctave));
    return dollied(start, factors, "slow dolly", 3);
}

std::vector<CameraPose> orbit_path(const SceneExtent& extent, const glm::vec3& up, int frames) {
    if (frames < kMinTemporalFrames)
        engine::fail("splat_lod::eval::orbit_path(): " + std::to_string(frames) + " frames are too few");
    const CameraPose start = orbit_poses(extent, up, 1).front();
    const glm::vec3 axis = glm::normalize(up);
    std::vector<CameraPose> poses;
    for (int i = 0; i < frames; ++i) {
        const float angle = 2.0f * 3.14159265f * static_cast<float>(i) / static_cast<float>(frames);
        const glm::mat3 turn(glm::rotate(glm::mat4(1.0f), angle, axis));
        CameraPose pose = start;
        pose.name = "orbit " + std::to_string(i);
        pose.eye = extent.centre + turn * (start.eye - extent.centre);
        pose.forward = glm::normalize(turn * start.forward);
        pose.up = glm::normalize(turn * start.up);
        poses.push_back(pose);
    }
    return poses;
}

std::string temporal_path_name(const std::filesystem::path& file) {
    std::string name = file.stem().string();
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
    if (name.empty()) name = "cameras";
    for (const std::string& taken : parse_name_list(kDefaultTemporalPaths, "paths"))
        if (name == taken) name += "_file";
    return name;
}

std::vector<TemporalPath> temporal_paths(const TemporalOptions& options, const CameraPose& first_view,
                                         const SceneExtent& extent, const glm::vec3& up) {
    std::vector<TemporalPath> paths;
    for (const std::string& name : parse_name_list(options.paths, "--temporal-paths")) {
        if (name == "dolly")
            paths.push_back({name, dolly_path(first_view, options.dolly_frames)});
        else if (name == "orbit")
            paths.push_back({name, orbit_path(extent, up, kOrbitFrames)});
        else if (name == "walk")
            paths.push_back({name, stride_path(first_view, kWalkSpeed, options.metres_per_unit, name)});
        else if (name == "run")
            paths.push_back({name, stride_path(first_view, kRunSpeed, options.metres_per_unit, name)});
        else if (name == "slow_dolly")
            paths.push_back({name, slow_dolly_path(first_view)});
    }
    if (options.path_file.empty()) return paths;
    std::vector<CameraPose> poses;
    try {
        poses = load_camera_set(options.path_file, extent, up);
    } catch (const engine::Error& e) {
        engine::fail(std::string("--temporal-path: ") + e.what());
    }
    if (static_cast<int>(poses.size()) < kMinTemporalFrames)
        engine::fail("--temporal-path " + options.path_file + ": " + std::to_string(poses.size()) +
                     " cameras are too few for a path (at least " + std::to_string(kMinTemporalFrames) + ")");
    paths.push_back({temporal_path_name(options.path_file), std::move(poses)});
    return paths;
}

void validate_temporal_options(const TemporalOptions& o) {
    if (o.width < 1 || o.height < 1) engine::fail("--width/--height: the image size must be positive");
    if (o.methods.empty()) engine::fail("--methods: no method given");
    std::vector<std::string> methods;
    for (const Method& method : o.methods) methods.push_back(method.name);
    fail_if_repeated(methods, "--methods");
    const std::vector<std::string> known = parse_name_list(kDefaultTemporalPaths, "paths");
    const std::vector<std::string> paths = parse_name_list(o.paths, "--temporal-paths");
    for (const std::string& path : paths)
        if (std::find(known.begin(), known.end(), path) == known.end())
            engine::fail("--temporal-paths: unknown path \"" + path + "\" (expected some of " + kDefaultTemporalPaths +
                         ")");
    fail_if_repeated(paths, "--temporal-paths");
    if (!(o.metres_per_unit > 0.0) || !std::isfinite(o.metres_per_unit))
        engine::fail("--metres-per-unit: must be a finite number > 0, got " + std::to_string(o.metres_per_unit));
    if (o.dolly_frames < kMinTemporalFrames)
        engine::fail("--temporal-frames: " + std::to_string(o.dolly_frames) + " frames are too few (at least " +
                     std::to_string(kMinTemporalFrames) + ")");
    if (!o.path_file.empty()) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(o.path_file, ec))
            engine::fail("--temporal-path " + o.path_file +
                         ": no such file (expected a camera-path JSON or an "
                         "INRIA cameras.json)");
    }
    if (temporal_supersampling(o.width, o.height, o.max_reference_side) == 0)
        engine::fail("--max-reference-side: " + std::to_string(o.max_reference_side) + " is smaller than the output " +
                     size_text(o.width, o.height) + "; the temporal sweep's reference needs at least the output size");
}

}  // namespace splat_lod::eval
