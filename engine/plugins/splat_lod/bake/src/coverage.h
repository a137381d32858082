#pragma once
// Internal to the bake (docs/algorithms.md §4): step 1, the pixel coverage of every Gaussian in every bake camera,
// and the order statistics the later steps take of it.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/bake/bake.h"
#include "splat_lod/core/reference_renderer.h"

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

// Linear interpolation between order statistics (numpy's default): p in [0, 100]. `values` is
// sorted in place; empty → −1.
double percentile(std::vector<double>& values, double p);

// Step 1's table for `cloud` in `cameras`. Throws engine::Error when no camera sees any Gaussian.
CoverageTable measure_coverage(const SplatCloud& cloud, const std::vector<reference::ReferenceCamera>& cameras,
                               const BakeOptions& options);

}  // namespace splat_lod::bake::detail
