// Step 1 of the bake: coverage (coverage.h).
#include "coverage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/core/error.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/lod_selection.h"
#include "splat_lod/core/parallel_for.h"

namespace splat_lod::bake::detail {

namespace {

constexpr std::size_t kChunk = 4096;  // Gaussians per parallel task

// The scale-1 coverage of a projected Gaussian, or −1 when the camera does not see it (its centre
// outside the image widened by `margin` × its size on every side).
double seen_coverage(const reference::ProjectedGaussian& g, const reference::ReferenceCamera& camera, double margin) {
    const double mx = margin * camera.width, my = margin * camera.height;
    if (!(g.mean.x >= -mx && g.mean.x < camera.width + mx && g.mean.y >= -my && g.mean.y < camera.height + my))
        return -1.0;
    return projected_coverage(g);
}

void fill_rows(std::vector<float>& values, std::size_t row_offset, const SplatCloud& cloud, std::size_t begin,
               const std::vector<reference::ReferenceCamera>& cameras, double znear, double margin, int threads) {
    const auto settings = coverage_settings(znear);
    std::vector<reference::detail::InstanceFrame> frames;
    frames.reserve(cameras.size());
    for (const auto& camera : cameras)
        frames.push_back(reference::detail::make_instance_frame(cloud, glm::dmat4(1.0), camera, settings, 0));
    const std::size_t count = cloud.size() - begin;
    const std::size_t tasks = (count + kChunk - 1) / kChunk;
    const std::size_t stride = cameras.size();
    reference::detail::parallel_for(tasks, reference::detail::resolve_thread_count(threads), [&](std::size_t task) {
        const std::size_t first = begin + task * kChunk;
        const std::size_t last = std::min(cloud.size(), first + kChunk);
        for (std::size_t i = first; i < last; ++i)
            for (std::size_t c = 0; c < stride; ++c) {
                const auto g = reference::detail::project_in_frame(cloud, i, frames[c], cameras[c], settings);
                values[(row_offset + i - begin) * stride + c] =
                    static_cast<float>(seen_coverage(g, cameras[c], margin));
            }
    });
}

}  // namespace

reference::ReferenceSettings coverage_settings(double znear) {
    reference::ReferenceSettings settings;
    settings.znear = znear;
    settings.dilation = 0.0;
    settings.sh_degree_cap = 0;  // colour is not needed
    return settings;
}

double projected_coverage(const reference::ProjectedGaussian& g) {
    using reference::CullReason;
    // `outside` only says the α ≥ 1/255 box covers no pixel centre: a Gaussian much smaller than a
    // pixel is still there (and is exactly the kind the bake pools). `degenerate` (a zero-area
    // projection) has coverage 0.
    if (g.cull == CullReason::degenerate) return 0.0;
    if (g.cull != CullReason::none && g.cull != CullReason::outside) return -1.0;
    return pixel_coverage(g.cov2d.x, g.cov2d.y, g.cov2d.z, g.opacity);
}

void CoverageTable::append(const SplatCloud& cloud, std::size_t begin,
                           const std::vector<reference::ReferenceCamera>& cameras, double znear, int threads) {
    if (cameras.size() != cameras_) engine::fail("bake: coverage table built for a different camera count");
    if (begin != gaussians()) engine::fail("bake: coverage rows must be appended in order");
    const std::size_t old_rows = gaussians();
    values_.resize(cloud.size() * cameras_, -1.0f);
    fill_rows(values_, old_rows, cloud, begin, cameras, znear, margin_, threads);
}

void CoverageTable::recompute(const SplatCloud& cloud, const std::vector<reference::ReferenceCamera>& cameras,
                              double znear, int threads) {
    values_.assign(cloud.size() * cameras_, -1.0f);
    fill_rows(values_, 0, cloud, 0, cameras, znear, margin_, threads);
}

double coverage_in_camera(const SplatCloud& cloud, std::size_t index, const reference::ReferenceCamera& camera,
                          double znear, double margin) {
    const auto settings = coverage_settings(znear);
    const auto frame = reference::detail::make_instance_frame(cloud, glm::dmat4(1.0), camera, settings, 0);
    return seen_coverage(reference::detail::project_in_frame(cloud, index, frame, camera, settings), camera, margin);
}

double percentile(std::vector<double>& values, double p) {
    if (values.empty()) return -1.0;
    std::sort(values.begin(), values.end());
    const double position = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
    const auto lower = static_cast<std::size_t>(std::floor(position));
    const std::size_t upper = std::min(lower + 1, values.size() - 1);
    const double fraction = position - static_cast<double>(lower);
    return values[lower] + fraction * (values[upper] - values[lower]);
}

// Step 1's table: the coverage of every Gaussian in every camera. Fails when no camera sees any.
CoverageTable measure_coverage(const SplatCloud& cloud, const std::vector<reference::ReferenceCamera>& cameras,
                               const BakeOptions& options) {
    CoverageTable table(cameras.size(), options.view_margin);
    table.append(cloud, 0, cameras, options.znear, options.threads);
    std::size_t seen = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto row = table.row(i);
        seen += std::any_of(row.begin(), row.end(), [](float s) { return s >= 0.0f; });
    }
    if (seen == 0)
        engine::fail("bake: none of the " + std::to_string(cameras.size()) + " cameras sees any of the " +
                     std::to_string(cloud.size()) +
                     " Gaussians (in front of it, centre inside its image, opacity above 1/255)");
    return table;
}

}  // namespace splat_lod::bake::detail
