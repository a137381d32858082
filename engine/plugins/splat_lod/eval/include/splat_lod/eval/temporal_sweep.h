#pragma once
// The temporal sweep: every method renders camera paths frame by frame, and its frame-to-frame
// change is compared with the reference's. For consecutive frames t−1, t of a path the pair error is
//   mean over pixels and RGB channels of |(M_t − M_{t−1}) − (R_t − R_{t−1})|
// in 8-bit units (0..255), where M is the method's frame and R the reference: the baseline render of
// the fine model at s·W × s·H area-averaged by s×s, with s the largest integer ≤ 4 for which the
// supersampled frame fits in max_reference_side. A method whose error against the reference stays
// the same from frame to frame (a steady blur, a constant bias) scores 0; popping, flicker and
// swimming score. The temporal error of a path is the mean pair error.
//
// Paths (TemporalOptions::paths picks them): `dolly` (the first view of the camera set dollied from
// 1× to 64× its distance and back, geometric steps), `orbit` (a level circle around the scene), `walk`
// and `run` (the first view stepping back along its view ray at 1.4 and 5 m/s, 60 frames a second,
// until its distance has doubled, in the scene's units at metres_per_unit), `slow_dolly` (1× to 16×
// at 1/32 octave a frame) and, when given, a camera file's sequence named by its stem.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "splat_lod/core/camera_set.h"
#include "splat_lod/eval/eval_method.h"
#include "splat_lod/eval/image_metrics.h"

namespace splat_lod::eval {

class FrameMeasurer;

constexpr int kMinTemporalFrames = 4;          // every path: the strip shows 4 consecutive frames
constexpr int kDefaultDollyFrames = 48;        // --temporal-frames
constexpr int kOrbitFrames = 24;               // the orbit path's frames
constexpr float kDollyMaxFactor = 64.0f;       // the dolly path's turning point
constexpr int kMaxTemporalSupersampling = 4;   // s ≤ 4
constexpr int kStripFrames = 4;                // consecutive frames in a strip
constexpr float kStripDifferenceGain = 4.0f;   // the strip's switch-difference row, brightened
constexpr double kPathFramesPerSecond = 60.0;  // walk and run
constexpr double kWalkSpeed = 1.4;             // m/s
constexpr double kRunSpeed = 5.0;              // m/s
constexpr double kStrideMaxFactor = 2.0;       // walk and run end at twice the first view's distance...
constexpr int kMaxStrideFrames = 360;          // ...or after 6 s, whichever comes first
constexpr int kSlowDollyStepsPerOctave = 32;   // the slow dolly's 1/32 octave a frame
constexpr double kSlowDollyMaxFactor = 16.0;   // the slow dolly's last frame
inline constexpr const char* kDefaultTemporalPaths = "dolly,orbit,walk,run,slow_dolly";

struct TemporalOptions {
    std::string scene_name = "scene";
    int width = 512;
    int height = 384;
    std::vector<Method> methods;
    int max_reference_side = 2048;
    int dolly_frames = kDefaultDollyFrames;     // the whole dolly, out and back
    std::string paths = kDefaultTemporalPaths;  // comma-separated, run in this order (--temporal-paths)
    double metres_per_unit = 1.0;               // the scene's scale, for walk and run (--metres-per-unit)
    std::string path_file;                      // a camera-path or INRIA cameras.json; empty: none
    // Called before each frame with "[i/n] scene path frame f (temporal)".
    std::function<void(const std::string&)> progress;
};

// A camera path rendered frame by frame.
struct TemporalPath {
    std::string name;  // a name of kDefaultTemporalPaths or the camera file's stem; letters, digits, '-', '_', '.'
    std::vector<CameraPose> poses;
};

// One method on one path: a row of temporal.csv and the curves of its plot.
struct TemporalRow {
    std::string method;
    std::string path;
    int frames = 0;
    double temporal_error = 0.0;   // the mean of pair_errors (8-bit units)
    double pop_peak = 0.0;         // the largest of pair_pops (8-bit units)
    double pop_mean = 0.0;         // the mean of pair_pops
    double switch_pop_peak = 0.0;  // the largest of pair_switch_pops (8-bit units)
    double switch_pop_mean = 0.0;  // the mean of pair_switch_pops
    double psnr_mean = 0.0;        // the mean of psnr (dB; +inf when every frame matches exactly)
    std::optional<double> splat_ms_mean;
    std::vector<double> pair_errors;       // index t−1: the pair (t−1, t)
    std::vector<double> pair_pops;         // index t−1: temporal_pair_pop of the pair (t−1, t)
    std::vector<double> pair_switch_pops;  // index t−1: selection_switch_pop of the pair (t−1, t)
    std::vector<double> psnr;              // per frame, against the reference frame
    std::vector<double> splat_ms;          // per frame, the "splat" GPU span (absent spans are left out)
};

// The frames around a path's largest switch pop (the pair where the selection's change shows most):
// the reference and every method (rows), frames first_frame … first_frame + 3 (columns), and for each
// pair the peak method's |M_t − M_t with the selection of t−1| (what switched).
struct TemporalStrip {
    std::string path;
    std::string peak_method;
    int peak_frame = 0;     // the peak pair is (peak_frame − 1, peak_frame)
    double peak_pop = 0.0;  // its switch pop
    int first_frame = 0;
    std::vector<std::string> rows;                   // "reference", then the methods
    std::vector<std::vector<engine::Image>> images;  // [row][column], W×H
    std::vector<engine::Image> differences;          // kStripFrames − 1 pairs, W×H, the switch difference × gain
};

struct TemporalResults {
    TemporalOptions options;
    int supersampling = 1;
    std::vector<std::string> paths;  // in the order run
    std::vector<TemporalRow> rows;   // path by path, methods in their order
    std::vector<TemporalStrip> strips;
};

// The supersampling factor: the largest s ≤ 4 with s·width and s·height ≤ max_reference_side; 0
// when not even the output size fits.
int temporal_supersampling(int width, int height, int max_reference_side);

// The pair error of two consecutive frames (8-bit units). Throws engine::Error when sizes differ.
double temporal_pair_error(const FloatImage& method_previous, const FloatImage& method,
                           const FloatImage& reference_previous, const FloatImage& reference);
// The pop of two consecutive frames, the measure that a fade lowers and a pop does not: the
// kPopPercentile quantile over pixels (nearest rank) of |(M_t − M_{t−1}) − (R_t − R_{t−1})| averaged over
// RGB, in 8-bit units. A level that switches in one frame over more than 0.1 % of the image counts at its
// full size where the pair error averages it away; faded over k frames it counts 1/k per pair; change that
// the reference has too (the camera's motion) cancels. Throws engine::Error when sizes differ.
inline constexpr double kPopPercentile = 0.999;
double temporal_pair_pop(const FloatImage& method_previous, const FloatImage& method,
                         const FloatImage& reference_previous, const FloatImage& reference);
// The switch pop of a pair: what the selection's change alone does to frame t. `frozen` is frame t
// drawn with frame t−1's selection (CameraView::selection_view = the view of t−1: the coverage, level
// weights and skipped clusters of t−1, the camera of t), `image` frame t as drawn; the kPopPercentile
// quantile over pixels of |M_t − frozen| averaged over RGB, in 8-bit units. The camera's motion, and
// the aliasing it moves, cancel exactly; a method without a selection (baseline) scores 0; a Gaussian
// switching on counts whole, faded in over k frames 1/k a pair. Throws engine::Error when sizes differ.
double selection_switch_pop(const FloatImage& frozen, const FloatImage& image);
// `view` selecting as `previous` does: the `frozen` frame of selection_switch_pop.
engine::CameraView with_selection_of(const engine::CameraView& view, const engine::CameraView& previous);
// |(M_t − M_{t−1}) − (R_t − R_{t−1})| per pixel, averaged over RGB, times `gain`, as grey RGBA8.
engine::Image temporal_difference_image(const FloatImage& method_previous, const FloatImage& method,
                                        const FloatImage& reference_previous, const FloatImage& reference, float gain);
// The pair errors of two equally long frame sequences: element t−1 for the pair (t−1, t).
std::vector<double> temporal_pair_errors(const std::vector<FloatImage>& method,
                                         const std::vector<FloatImage>& reference);

// `frames` poses from `start` dollied out to kDollyMaxFactor and back: the first ⌈frames/2⌉ go from
// 1× to 64× inclusive, the rest come back with the last at 1×, all in geometric steps.
std::vector<CameraPose> dolly_path(const CameraPose& start, int frames);
// The first view stepping back along its view ray by `speed` m/s at kPathFramesPerSecond, the scene's
// unit being `metres_per_unit` metres: from 1× its focus distance until kStrideMaxFactor× (the last
// frame at or just past it) or kMaxStrideFrames steps. `name` names the poses ("walk 3 (1.07x)").
std::vector<CameraPose> stride_path(const CameraPose& start, double speed, double metres_per_unit,
                                    const std::string& name);
// 1× to kSlowDollyMaxFactor× in steps of 1/kSlowDollyStepsPerOctave octave (129 frames).
std::vector<CameraPose> slow_dolly_path(const CameraPose& start);
// `frames` views on a level circle around the scene at the first orbit camera's distance and
// elevation (orbit_poses(extent, up, 1)), turning once about `up` in equal steps.
std::vector<CameraPose> orbit_path(const SceneExtent& extent, const glm::vec3& up, int frames = kOrbitFrames);
// The path name of a camera file: its stem with characters other than letters, digits, '-', '_'
// and '.' replaced by '_'; "_file" is appended when that gives a name of kDefaultTemporalPaths.
std::string temporal_path_name(const std::filesystem::path& file);
// The paths of options.paths in their order (dolly, walk, run and slow_dolly from first_view), and the
// camera file's path when options.path_file is given. Throws engine::Error naming --temporal-path
// when that file holds fewer than kMinTemporalFrames cameras or cannot be read.
std::vector<TemporalPath> temporal_paths(const TemporalOptions& options, const CameraPose& first_view,
                                         const SceneExtent& extent, const glm::vec3& up);

// Throws engine::Error before anything is rendered when no method is given, a method repeats, a
// path of --temporal-paths is unknown or repeats, --metres-per-unit is not a finite number > 0,
// --temporal-frames is below kMinTemporalFrames, --temporal-path names no file, or the reference
// cannot be supersampled within max_reference_side.
void validate_temporal_options(const TemporalOptions& options);
// Renders every path with the reference and every method; also validates the options and that
// every path has at least kMinTemporalFrames poses.
TemporalResults run_temporal_sweep(FrameMeasurer& measurer, const std::vector<TemporalPath>& paths,
                                   const TemporalOptions& options);

// temporal.csv: method,path,frames,temporal_error,psnr_mean,splat_ms_mean,pop_peak,pop_mean,
// switch_pop_peak,switch_pop_mean.
void write_temporal_csv(const TemporalResults& results, const std::filesystem::path& path);
// The strip of one path: a header of frame numbers, one row per image source, the peak method's
// differences below.
engine::Image temporal_strip_image(const TemporalStrip& strip);
// Into `folder` (created): temporal.csv, temporal.md, temporal_<path>.png (gnuplot, through
// temporal.gp and temporal_<path>_<method>.dat; skipped with a warning without gnuplot) and
// temporal_strip_<path>.png. `renderer` is the GL renderer string, quoted in temporal.md.
void write_temporal_outputs(const TemporalResults& results, const std::string& renderer,
                            const std::filesystem::path& folder);

}  // namespace splat_lod::eval
