#pragma once
// The LOD bake (Yan et al. Algorithm 1 and supplement §9, docs/algorithms.md §4): from a trained
// scene (level 1 only) and a set of cameras, builds levels 2..4 by pooling the Gaussians that are
// small at the level's render scale 4^(l−1), enlarges them, gives every Gaussian the coverage
// range in which it is drawn (10th/90th percentiles over the cameras), and refines the colour and
// opacity of each coarse level against area-averaged renders of the fine model (the fine model is
// the teacher: the bake has no photos). The result is ordered coarse levels first and spatially
// clustered within a level, so a streamer can load a coarse prefix.
//
// All on the CPU and GL-free: the coverage and the refinement use the reference projection, so a
// bake gives the same result on any machine and any thread count.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/msgs/lod_rule.h"

namespace splat_lod::bake {

inline constexpr int kMaxLevel = 4;

// Render scale (per side) at which level l's coverage is measured: 4^(l−1).
constexpr int level_scale(int level) {
    return 1 << (2 * (level - 1));
}

// How small Gaussians are grouped into the cells that each become one coarse Gaussian.
enum class CellRule {
    grid,      // docs/algorithms.md §4 steps 2–3: ceil(grid_cells / l)³ cells over the normalised cube
    adaptive,  // the larger of the grid cell and the distance-adaptive cell (S_T…2·S_T px at scale k)
};

// How a cell's Gaussians become one.
enum class PoolingRule {
    mean,     // docs/algorithms.md §4 steps 4–5: mean parameters, scales enlarged by clamp(S_T / S_avg, 1, max)
    moments,  // the moment-matched Gaussian of the members (covers the cell they fill), no enlargement
};

struct BakeOptions {
    int coarsest_level = kMaxLevel;  // build levels 2..coarsest_level (1 = ranges only)
    // The selection rule the bake is made for: its S_T sets which Gaussians are pooled, its S_rel_min
    // and S_rel_max the refinement's selection (drawn in mode full with hard switching).
    plugin_msgs::LodRule rule;
    double znear = 0.2;  // cameras see Gaussians with z > znear
    // A camera sees a Gaussian whose centre lies inside its image widened by this fraction of the
    // width and height on every side (0: the image itself). Content just outside every bake view
    // still reaches the border pixels of nearby views; with a margin it gets ranges and coarse levels.
    double view_margin = 0.0;
    // Every scale of a pooled Gaussian is raised to at least this fraction of its largest (0: as
    // pooled). A thin coarse Gaussian seen edge-on has a tiny coverage and passes "not too large"
    // in views where its finer members are drawn.
    double min_axis_ratio = 0.0;
    int grid_cells = 400;  // level l uses ceil(grid_cells / l)³ cells over [−2, 2]³
    CellRule cells = CellRule::adaptive;
    PoolingRule pooling = PoolingRule::mean;
    // Bake twice, with (adaptive cells, enlargement ≤ 8) and (grid cells, enlargement ≤ 32), and
    // keep the adaptive result unless the grid one's levels score a mean PSNR at least 0.5 dB higher
    // on the refinement cameras: neither wins everywhere (docs/lod.md, "Two cell recipes, chosen per
    // scene", has the scores per scene). Needs the refinement (its cameras and targets); `cells` and `max_enlargement`
    // are ignored while it is on.
    bool choose_recipe = true;
    double max_enlargement = 8.0;  // clamp of S_T / S_avg
    // Cap each coarse Gaussian's coverage_max at the coverage where its members stop being drawn
    // (cap_coverage_max in bake/src/ranges.h): the percentiles alone let a coarse Gaussian seen closer or
    // more face-on by a bake camera than by a view be drawn on top of the members that view draws.
    bool member_ranges = false;
    double range_low_percentile = 10.0;
    double range_high_percentile = 90.0;

    // Refinement (step 7): Adam on SH DC and opacity logit of each coarse level.
    int refine_iterations = 200;  // per level; 0 switches the refinement off
    int refine_cameras = 16;      // at most this many bake cameras (evenly spread); 0: all of them
    double learning_rate_dc = 0.02;
    double learning_rate_opacity = 0.1;
    double logit_clamp = 9.2;
    bool ranges_after_refine = true;  // measure the ranges again after the refinement
    std::uint64_t seed = 1;           // camera order of the refinement

    glm::dvec3 background{0.0};  // behind the splats in the refinement's renders
    // When set, the refinement writes level<l>_{target,before,after}.png of its first camera here.
    std::string debug_image_dir;
    int threads = 0;  // 0: hardware concurrency

    // Called at the start of each stage and as it advances: stage name, fraction done in [0, 1].
    std::function<void(const std::string& stage, double fraction)> progress;
};

// Throws engine::Error naming the first impossible setting.
void validate(const BakeOptions& options);

struct LevelSummary {
    int level = 0;
    int scale = 1;                  // 4^(l−1)
    std::size_t candidates = 0;     // Gaussians of finer levels seen by a camera
    std::size_t small = 0;          // of those, below S_T at this scale in some camera
    std::size_t added = 0;          // pooled Gaussians (non-empty cells)
    double mean_enlargement = 1.0;  // mean of clamp(S_T / S_avg, 1, max)
    std::size_t at_max_enlargement = 0;
    // Refinement: mean PSNR (dB) of the level's scale-k renders against the targets over the
    // refinement cameras, before and after; NaN when it did not run.
    double refine_psnr_before = 0.0;
    double refine_psnr_after = 0.0;
    double refine_psnr_baseline = 0.0;                       // level 1 alone, unfiltered, on the same cameras
    double final_psnr = 0.0;                                 // `full` at this scale once the whole bake is done
    std::array<double, kMaxLevel> refine_drawn_per_level{};  // mean over the cameras of the selection
    int refine_iterations = 0;
};

struct StageTime {
    std::string stage;
    double seconds = 0.0;
};

struct BakeSummary {
    std::size_t input_gaussians = 0;
    std::size_t output_gaussians = 0;
    std::size_t cameras = 0;
    std::size_t unseen = 0;              // Gaussians no camera sees (ranges unset)
    double normalisation_radius = 0.0;   // B of docs/algorithms.md §4 step 2
    bool radius_from_gaussians = false;  // the camera positions coincide: B from the Gaussians
    std::vector<LevelSummary> levels;    // one per built level 2..coarsest
    std::vector<StageTime> stages;
    std::size_t peak_memory_bytes = 0;  // process peak resident set (0 where unknown)
    std::vector<std::string> warnings;
    std::string recipe;                                         // "adaptive cells, enlargement <= 8" or the grid one
    std::vector<std::pair<std::string, double>> recipe_scores;  // mean final PSNR per recipe tried

    double added_fraction() const;
};

// Bakes `fine` (every Gaussian level 1; LOD attributes already present are an error) seen by
// `cameras`. Throws engine::Error when the scene is empty, there are no cameras, or no camera sees
// any Gaussian.
SplatCloud bake_lod(const SplatCloud& fine, const std::vector<reference::ReferenceCamera>& cameras,
                    const BakeOptions& options, BakeSummary* summary = nullptr);

// A human-readable multi-line summary (Gaussians per level, time per stage, memory).
std::string format_summary(const BakeSummary& summary);

}  // namespace splat_lod::bake
