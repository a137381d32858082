#pragma once
// The sweeps of the evaluation (docs/algorithms.md §6) over a camera set and a list of methods:
//   scale k:    each method at (W/k)×(H/k), same field of view, against the baseline render of the
//               fine model at W×H area-averaged by k×k;
//   distance d: each method at W×H with the camera d times farther from its target (the scene
//               covers 1/d of its screen size), against the baseline at (dW)×(dH) area-averaged
//               by d×d where that fits in max_reference_side, with no error reported beyond;
//   upscale f:  each upscaler variant renders the splats at render scale 1/f and upscales them to
//               W×H (docs/algorithms.md §5), against the native render (render scale 1, same LOD mode) at
//               W×H; the native render is also measured as method "native", factor 1, the time
//               base of the speed-ups.
// Comparison scenes (another model of the same content, e.g. each level of an existing LOD chain)
// join the scale sweep: each is rendered with the baseline at every scale and view and scored
// against the main scene's references, so that their errors and the methods' are comparable.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "splat_lod/msgs/splat_statistics.h"

#include "engine/render/image.h"
#include "splat_lod/core/camera_set.h"
#include "splat_lod/eval/eval_method.h"
#include "splat_lod/eval/eval_scene.h"

namespace splat_lod::eval {

class FrameMeasurer;

enum class Sweep { scale, distance, upscale, storage };
const char* sweep_name(Sweep sweep);

// A scene measured against the main scene's references (scale sweep only).
struct ComparisonScene {
    std::string method;       // the method name its measurements carry ("chain_L3")
    std::string description;  // for the report
    // Called once, when its turn comes; the scene is dropped after its measurements, so only one
    // comparison scene is in memory at a time.
    std::function<EvalScene()> load;
};

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
    // The upscale sweep: factors (≥ 2, leaving at least kMinUpscaleSource pixels per side), the
    // upscaler variants, and the LOD mode (a method of the registry) of both native and upscaled.
    std::vector<int> upscale_factors{2, 3, 4, 8};
    std::vector<UpscalerVariant> upscalers = select_upscalers("spline,bicubic,bilinear,lanczos3,spline_plain");
    std::string upscale_mode = "baseline";
    int sheet_tile_width = 0;  // contact-sheet tile width in pixels; 0: width / 4
    // Contact-sheet rows after the reference; empty: every method of `methods` (comparison scenes
    // appear only when named here).
    std::vector<std::string> sheet_methods;
    std::vector<ComparisonScene> comparisons;
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
    std::vector<ContactTile> level_tiles;  // the level picture, method "full"
    int max_reference_distance = 0;        // largest distance with an error measurement
    // The first view of the upscale sweep at its crop factors (upscale_crop_factors): "native"
    // (factor 1) and each upscaler's output, all W×H.
    std::vector<ContactTile> upscale_tiles;
};

// The scales of the level picture (levels.png): the first view with `full` and each Gaussian
// tinted by its level, at those of these scales that fit the size. Rendered when `full` is measured.
constexpr int kLevelPictureScales[] = {1, 4, 16, 64};

// The upscale sweep's smallest low-resolution side: below it the upscalers' footprints (Lanczos-3:
// 6 texels) mostly clamp at the border, and nothing is learned about them.
constexpr int kMinUpscaleSource = 6;
// The low-resolution side the splat pass rasterises for an output side at factor f: ⌈side / f⌉.
constexpr int upscale_source_side(int side, int factor) {
    return (side + factor - 1) / factor;
}
// The factors of the side-by-side crops: 3 and 4 where measured, else the first factor.
std::vector<int> upscale_crop_factors(const EvalOptions& options);

// Throws engine::Error before any rendering when a scale or distance is impossible for the size,
// a comparison scene lacks the scale sweep or repeats a method name, a contact-sheet row names
// nothing measured, or (when the upscale sweep runs) an upscale factor is below 2, repeated or too
// large for the size, no upscaler is given, or the upscale mode is unknown.
void validate_options(const EvalOptions& options);
// The method names measured in a sweep, in the order of `methods` then `comparisons`; for the
// upscale sweep "native" then the upscalers.
std::vector<std::string> measured_methods(const EvalOptions& options, Sweep sweep);
EvalResults run_evaluation(FrameMeasurer& measurer, const std::vector<CameraPose>& poses, const EvalOptions& options);

}  // namespace splat_lod::eval
