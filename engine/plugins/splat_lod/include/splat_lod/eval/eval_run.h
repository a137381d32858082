#pragma once
// The two sweeps of the evaluation (ALGORITHMS §6) over a camera set and a list of methods:
//   scale k:    each method at (W/k)×(H/k), same field of view, against the baseline render of the
//               fine model at W×H area-averaged by k×k;
//   distance d: each method at W×H with the camera d times farther from its target (the scene
//               covers 1/d of its screen size), against the baseline at (dW)×(dH) area-averaged
//               by d×d where that fits in max_reference_side, with no error reported beyond.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <plugin_msgs/splat_statistics.h>

#include "engine/render/image.h"
#include "splat_lod/eval/camera_set.h"
#include "splat_lod/eval/eval_method.h"

namespace splat_lod::eval {

class FrameMeasurer;

enum class Sweep { scale, distance };
const char* sweep_name(Sweep sweep);

struct EvalOptions {
    std::string scene_name = "scene";
    int width = 512;
    int height = 384;
    int frames = 5;
    int warmup = 2;
    std::vector<Method> methods;
    std::vector<Sweep> sweeps{Sweep::scale};
    std::vector<int> scales{1, 2, 4, 8, 16, 32, 64, 128};
    std::vector<int> distances{1, 2, 4, 8, 16, 32, 64, 128};
    int max_reference_side = 2048;
    int sheet_tile_width = 0;  // contact-sheet tile width in pixels; 0: width / 4
    // Called before each measurement with "[i/n] scene view v method k× (sweep)".
    std::function<void(const std::string&)> progress;
};

// One method, one view, one scale or distance: a row of the CSV.
struct Measurement {
    std::string scene;
    Sweep sweep = Sweep::scale;
    int view = 0;
    std::string view_name;
    std::string method;
    int factor = 1;  // the scale k or the distance d
    int width = 0, height = 0;
    std::optional<double> psnr, ssim;  // absent where no reference was rendered
    double wall_ms = 0.0;
    std::map<std::string, double> gpu_ms;
    plugin_msgs::SplatStatistics statistics;
};

// An image of the first view for the contact sheet; method "reference" is the area-averaged
// reference.
struct ContactTile {
    std::string method;
    int factor = 1;
    engine::Image image;
};

struct EvalResults {
    EvalOptions options;
    int views = 0;
    std::vector<Measurement> rows;
    std::vector<ContactTile> tiles;
    int max_reference_distance = 0;  // largest distance with an error measurement
};

// Throws engine::Error before any rendering when a scale or distance is impossible for the size.
void validate_options(const EvalOptions& options);
EvalResults run_evaluation(FrameMeasurer& measurer, const std::vector<CameraPose>& poses, const EvalOptions& options);

}  // namespace splat_lod::eval
