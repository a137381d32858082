#pragma once
// Internal to the bake: the steps of docs/algorithms.md §4, each a function so that tests can check it on
// hand-made input (closed forms, hard cases) without running a whole bake.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/bake/bake.h"
#include "splat_lod/core/splat_math.h"

namespace splat_lod::bake::detail {

// Pixel coverage at full resolution (scale 1) of every Gaussian in every camera, −1 where the
// camera does not see it: seen means in front (z > znear), centre inside the image widened by
// `margin` × its width and height on every side (BakeOptions::view_margin; 0: the image itself) and
// opacity > 1/255. Coverage at scale k is the scale-1 value / k exactly (Σ2D scales with f², the image
// and the Jacobian clamp with f), so one table serves every level.
class CoverageTable {
public:
    explicit CoverageTable(std::size_t cameras = 0, double margin = 0.0) : cameras_(cameras), margin_(margin) {}
    std::size_t cameras() const { return cameras_; }
    std::size_t gaussians() const { return cameras_ == 0 ? 0 : values_.size() / cameras_; }
    float at(std::size_t gaussian, std::size_t camera) const { return values_[gaussian * cameras_ + camera]; }
    std::span<const float> row(std::size_t gaussian) const { return {values_.data() + gaussian * cameras_, cameras_}; }

    // Computes rows for Gaussians [begin, cloud.size()) and appends them (rows before `begin`
    // must already be there).
    void append(const SplatCloud& cloud, std::size_t begin, const std::vector<reference::ReferenceCamera>& cameras,
                double znear, int threads);
    // Recomputes every row (e.g. after opacities changed).
    void recompute(const SplatCloud& cloud, const std::vector<reference::ReferenceCamera>& cameras, double znear,
                   int threads);

private:
    std::size_t cameras_ = 0;
    double margin_ = 0.0;
    std::vector<float> values_;
};

// Coverage is defined on the undilated covariance (docs/algorithms.md §2): projection settings with no
// dilation, no mip filter and no colour.
reference::ReferenceSettings coverage_settings(double znear);
// The coverage of a Gaussian projected with coverage_settings(): −1 when culled before its 2D
// covariance exists (behind, invisible, non-finite), 0 for a degenerate projection.
double projected_coverage(const reference::ProjectedGaussian& g);

// Scale-1 coverage of one Gaussian in one camera, or −1 when the camera does not see it.
double coverage_in_camera(const SplatCloud& cloud, std::size_t index, const reference::ReferenceCamera& camera,
                          double znear, double margin = 0.0);

// Step 2: x' = (p − c)/B inside the unit cube, (2 − 1/‖x'‖∞)·x'/‖x'‖∞ outside; everything lands in
// [−2, 2]³ continuously (also for points at 1e6 units or beyond).
struct Normaliser {
    glm::dvec3 centre{0.0};
    double radius = 1.0;
    bool from_gaussians = false;

    glm::dvec3 apply(const glm::dvec3& p) const;
};
// c = mean camera position, B = half the largest axis span of the camera positions; when that is
// (near) zero (one camera, coincident cameras), half the largest axis span of the Gaussians'
// 1st–99th percentile bounds; 1 when that is zero too.
Normaliser make_normaliser(const std::vector<reference::ReferenceCamera>& cameras, const SplatCloud& cloud);

// Linear interpolation between order statistics (numpy's default): p in [0, 100]. `values` is
// sorted in place; empty → −1.
double percentile(std::vector<double>& values, double p);

// Step 3: the grid cell of a normalised position, with `cells` per side over [−2, 2]³.
std::uint64_t grid_cell(const glm::dvec3& normalised, int cells);

// The cell a small Gaussian at `p` pools into at `level`. Grid cells alone (step 3) are a fixed
// fraction of the camera span B, which at the coarse scales is far below a pixel for an object
// seen from around it (level 4: 0.04·B ≈ ¼ px at scale 64) and pools thousands of overlapping
// Gaussians. With CellRule::adaptive the cell is the larger of the grid cell and the
// distance-adaptive cell of docs/algorithms.md §4 (edge = 2·S_T·2^b·k/f for b = floor(log2 d), d the
// distance to the nearest camera centre, f its focal length): from its nearest camera a cell then
// spans at least S_T…2·S_T pixels at the level's scale. Keys of the two kinds never collide.
std::uint64_t cell_key(const glm::dvec3& p, int level, int grid_cells, const Normaliser& normaliser,
                       const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options);

using math::rotation_of;
using math::spread_bits;
using math::symmetric_eigen;

// Step 4: the pooled Gaussian of `members` (indices into `source`), written at `out` of `target`
// (which has the same SH degree and extras): mean position, quaternions flipped to the first member's
// hemisphere then averaged and renormalised, mean log-scales, mean activated opacity (back to a
// logit clamped to [1e−4, 1 − 1e−4]), mean SH coefficients and extra attributes.
void pool(const SplatCloud& source, std::span<const std::uint32_t> members, SplatCloud& target, std::size_t out);

// Like pool(), but position, rotation and scales are those of the moment-matched Gaussian of the
// members weighted by opacity, Σ = Σ wᵢ(Σᵢ + (μᵢ − μ)(μᵢ − μ)ᵀ) / Σ wᵢ: it covers the region its
// members fill rather than their average size (PoolingRule::moments).
void pool_moments(const SplatCloud& source, std::span<const std::uint32_t> members, SplatCloud& target,
                  std::size_t out);

// Raises every scale of the Gaussian at `index` to at least `ratio` × its largest (0: unchanged), so
// that a coarse Gaussian is not a thin disc or needle whose coverage collapses when seen edge-on.
void thicken(SplatCloud& cloud, std::size_t index, double ratio);

// Step 5: S_avg = mean over members of each member's median coverage at `scale` over the
// cameras that see it; members seen by no camera are left out; 0 when none is seen.
double mean_median_coverage(const CoverageTable& table, std::span<const std::uint32_t> members, int scale);
// clamp(S_T / S_avg, 1, max); max when S_avg is 0.
double enlargement(double size_threshold, double mean_coverage, double max_enlargement);

// Step 6: coverage_min/max of every Gaussian at its own level's scale from the table.
void set_coverage_ranges(SplatCloud& cloud, const CoverageTable& table, double low_percentile, double high_percentile);

// The members of one coarse level's Gaussians: Gaussian first + g pooled
// members[starts[g] .. starts[g + 1]) (indices into the cloud).
struct LevelMembers {
    std::size_t first = 0;
    std::vector<std::uint32_t> members;
    std::vector<std::size_t> starts;
};

// Caps coverage_max of every coarse Gaussian that has one at the coverage where its members stop
// being drawn, so that it is not selected in views its members serve: a member m is drawn while
// its coverage is at least D_m = max(S_T, S_rel_min · coverage_min_m) (S_T alone when unset); in
// bake camera j the coarse Gaussian is r_j times the median member's coverage; with r and D the
// medians over cameras and members, the cap is r · D / S_rel_max (selected when S ≤ r · D).
void cap_coverage_max(SplatCloud& cloud, const CoverageTable& table, const std::vector<LevelMembers>& levels,
                      const BakeOptions& options);
// The cap for one coarse Gaussian from its coverage per camera (≤ 0: not seen), its members' and their
// coverage_min (≤ 0: unset); −1 when no camera sees it together with a member.
double member_cap(std::span<const float> coarse, const std::vector<std::span<const float>>& members,
                  std::span<const float> member_min, const BakeOptions& options);

// Output order: coarsest level first; within a level by size class (a factor of 2 in the extent
// that bounds coverage; Gaussians no camera saw last), then along a Morton curve of the normalised
// position (ties by index). A level is a contiguous prefix for streaming, and each run of 256 (a
// project workgroup) holds Gaussians of one size near each other, which the renderer can skip
// together when all are too small for the view (GpuCluster).
std::vector<std::uint32_t> output_order(const SplatCloud& cloud, const Normaliser& normaliser);

// Step 7 (refine.cpp): the distillation of each coarse level against the fine model. Holds the
// fine model's full-resolution renders (clamped to [0, 1]) of the refinement cameras, made once
// and area-averaged per level.
class Refiner {
public:
    // `fine` is the level-1 scene; `cameras` all bake cameras (the refinement picks its subset).
    Refiner(const SplatCloud& fine, const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options);
    bool usable() const { return !cameras_.empty(); }

    // Adam on the SH DC and opacity logit of `level`'s Gaussians of `cloud` (every level present,
    // ranges set), one camera per iteration; the selection (docs/algorithms.md §3, mode full) at the
    // level's scale is computed once per camera and held fixed.
    void refine_level(SplatCloud& cloud, int level, LevelSummary& summary) const;
    // Mean PSNR (dB) over the refinement cameras of the `full` selection of `cloud` at the level's
    // scale against the targets.
    double evaluate(const SplatCloud& cloud, int level) const;

private:
    BakeOptions options_;
    std::vector<reference::ReferenceCamera> cameras_;  // the refinement's subset
    std::vector<std::vector<double>> targets_;         // full-resolution RGB in [0, 1] per camera
};

// The cameras the refinement uses: image sides divisible by 64 and the focal length of the first
// such camera; at most `limit`, spread evenly over the set. Empty when none qualifies.
std::vector<std::size_t> refinement_cameras(const std::vector<reference::ReferenceCamera>& cameras, int limit);

// The camera at render scale k: focal lengths, principal point and size divided by k.
reference::ReferenceCamera scaled_camera(const reference::ReferenceCamera& camera, int k);

}  // namespace splat_lod::bake::detail
