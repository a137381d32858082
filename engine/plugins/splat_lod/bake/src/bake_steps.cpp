// Steps 1–6 of the bake (docs/algorithms.md §4) as separate functions; bake.cpp runs them in order.
#include "bake_steps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <glm/gtc/quaternion.hpp>

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

glm::dvec3 Normaliser::apply(const glm::dvec3& p) const {
    const glm::dvec3 x = (p - centre) / radius;
    const double norm = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    if (!std::isfinite(norm)) {
        // Beyond double range after the division: the direction still decides the face of the cube.
        const glm::dvec3 d = p - centre;
        const double m = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
        return m > 0.0 && std::isfinite(m) ? 2.0 * d / m : glm::dvec3(0.0);
    }
    if (norm <= 1.0) return x;
    return (2.0 - 1.0 / norm) * x / norm;
}

Normaliser make_normaliser(const std::vector<reference::ReferenceCamera>& cameras, const SplatCloud& cloud) {
    Normaliser n;
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest()), sum(0.0);
    for (const auto& camera : cameras) {
        lo = glm::min(lo, camera.position);
        hi = glm::max(hi, camera.position);
        sum += camera.position;
    }
    n.centre = cameras.empty() ? glm::dvec3(0.0) : sum / static_cast<double>(cameras.size());
    const glm::dvec3 span = cameras.empty() ? glm::dvec3(0.0) : hi - lo;
    n.radius = 0.5 * std::max({span.x, span.y, span.z});
    if (n.radius > 1e-9 && std::isfinite(n.radius)) return n;

    n.from_gaussians = true;
    n.radius = 0.0;
    if (!cloud.empty()) {
        double largest = 0.0;
        for (int axis = 0; axis < 3; ++axis) {
            std::vector<double> values(cloud.size());
            for (std::size_t i = 0; i < cloud.size(); ++i) values[i] = cloud.positions[i][axis];
            const double p1 = percentile(values, 1.0), p99 = percentile(values, 99.0);
            largest = std::max(largest, p99 - p1);
        }
        n.radius = 0.5 * largest;
    }
    if (!(n.radius > 1e-9) || !std::isfinite(n.radius)) n.radius = 1.0;
    return n;
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

std::uint64_t grid_cell(const glm::dvec3& normalised, int cells) {
    std::uint64_t key = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const double t = (normalised[axis] + 2.0) / 4.0 * cells;
        const auto index = static_cast<std::uint64_t>(std::clamp(std::floor(t), 0.0, static_cast<double>(cells - 1)));
        key = key * static_cast<std::uint64_t>(cells) + index;
    }
    return key;
}

std::uint64_t cell_key(const glm::dvec3& p, int level, int grid_cells, const Normaliser& normaliser,
                       const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options) {
    const glm::dvec3 x = normaliser.apply(p);
    const std::uint64_t grid_key = grid_cell(x, grid_cells);
    if (options.cells == CellRule::grid || cameras.empty()) return grid_key;
    // The grid cell's edge in world units near p: 4B/cells inside the unit cube, stretched by the
    // contraction (radial derivative 1/‖x‖∞²) outside it.
    const glm::dvec3 unscaled = (p - normaliser.centre) / normaliser.radius;
    const double norm = std::max({std::abs(unscaled.x), std::abs(unscaled.y), std::abs(unscaled.z), 1.0});
    const double grid_edge = 4.0 * normaliser.radius / grid_cells * norm * norm;
    double nearest = std::numeric_limits<double>::infinity();
    const reference::ReferenceCamera* camera = &cameras.front();
    for (const auto& c : cameras) {
        const double d = glm::length(p - c.position);
        if (d < nearest) {
            nearest = d;
            camera = &c;
        }
    }
    const double d = std::max(options.znear, nearest);
    const int b = static_cast<int>(std::floor(std::log2(d)));
    const double edge = 2.0 * double(options.rule.size_threshold_px) * std::ldexp(1.0, b) * level_scale(level) /
                        std::max(camera->fx, camera->fy);
    if (!(edge > grid_edge) || !std::isfinite(edge)) return grid_key & ~(1ULL << 63);
    // Distance cell: (b, floor(p / edge)) hashed into the 63 low bits, the top bit set.
    std::uint64_t hash = 1469598103934665603ULL ^ static_cast<std::uint64_t>(static_cast<std::int64_t>(b) + 1024);
    for (int axis = 0; axis < 3; ++axis) {
        const double cell = std::floor(p[axis] / edge);
        const auto index = static_cast<std::uint64_t>(static_cast<std::int64_t>(std::clamp(cell, -4e15, 4e15)));
        hash = (hash ^ index) * 1099511628211ULL;
        hash ^= hash >> 29;
    }
    return hash | (1ULL << 63);
}

using reference::detail::sigmoid;

void pool_moments(const SplatCloud& source, std::span<const std::uint32_t> members, SplatCloud& target,
                  std::size_t out) {
    pool(source, members, target, out);
    double weight_sum = 0.0;
    glm::dvec3 mean(0.0);
    for (const std::uint32_t m : members) {
        const double w = 1.0 / (1.0 + std::exp(-static_cast<double>(source.opacity_logits[m])));
        weight_sum += w;
        mean += w * glm::dvec3(source.positions[m]);
    }
    if (!(weight_sum > 0.0)) return;
    mean /= weight_sum;
    glm::dmat3 covariance(0.0);
    for (const std::uint32_t m : members) {
        const double w = 1.0 / (1.0 + std::exp(-static_cast<double>(source.opacity_logits[m])));
        const glm::dvec3 s = glm::exp(glm::dvec3(source.log_scales[m]));
        const glm::dmat3 rs = rotation_of(source.rotations[m]) * glm::dmat3(s.x, 0, 0, 0, s.y, 0, 0, 0, s.z);
        const glm::dvec3 d = glm::dvec3(source.positions[m]) - mean;
        covariance += w * (rs * glm::transpose(rs) + glm::outerProduct(d, d));
    }
    covariance /= weight_sum;
    glm::dvec3 values;
    glm::dmat3 vectors;
    symmetric_eigen(covariance, values, vectors);
    if (glm::determinant(vectors) < 0.0) vectors[2] = -vectors[2];
    const glm::dquat q = glm::normalize(glm::quat_cast(vectors));
    if (!std::isfinite(q.w + q.x + q.y + q.z)) return;  // keep pool()'s geometry
    target.positions[out] = glm::vec3(mean);
    target.rotations[out] = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
                             static_cast<float>(q.z)};
    for (int axis = 0; axis < 3; ++axis)
        target.log_scales[out][axis] = static_cast<float>(0.5 * std::log(std::max(values[axis], 1e-30)));
}

void pool(const SplatCloud& source, std::span<const std::uint32_t> members, SplatCloud& target, std::size_t out) {
    if (members.empty()) engine::fail("bake: pooling an empty cell");
    const double n = static_cast<double>(members.size());
    glm::dvec3 position(0.0), log_scale(0.0), dc(0.0);
    glm::dvec4 quaternion(0.0);
    double opacity = 0.0;
    const Rotation& first = source.rotations[members[0]];
    const glm::dvec4 reference_q(first.w, first.x, first.y, first.z);
    const std::size_t stride = source.sh_rest_stride();
    std::vector<double> rest(stride, 0.0);
    for (const std::uint32_t m : members) {
        position += glm::dvec3(source.positions[m]);
        log_scale += glm::dvec3(source.log_scales[m]);
        dc += glm::dvec3(source.sh_dc[m]);
        opacity += sigmoid(source.opacity_logits[m]);
        const Rotation& r = source.rotations[m];
        glm::dvec4 q(r.w, r.x, r.y, r.z);
        // q and −q are the same rotation: average on the first member's hemisphere.
        if (glm::dot(q, reference_q) < 0.0) q = -q;
        quaternion += q;
        for (std::size_t k = 0; k < stride; ++k) rest[k] += source.sh_rest[m * stride + k];
    }
    target.positions[out] = glm::vec3(position / n);
    target.log_scales[out] = glm::vec3(log_scale / n);
    target.sh_dc[out] = glm::vec3(dc / n);
    // Every flipped q has a non-negative dot with the first, so the sum has at least its length.
    const double length = glm::length(quaternion);
    const glm::dvec4 q = length > 0.0 ? quaternion / length : glm::dvec4(1.0, 0.0, 0.0, 0.0);
    target.rotations[out] = {static_cast<float>(q[0]), static_cast<float>(q[1]), static_cast<float>(q[2]),
                             static_cast<float>(q[3])};  // (w, x, y, z), the order of reference_q
    const double mean_opacity = std::clamp(opacity / n, 1e-4, 1.0 - 1e-4);
    target.opacity_logits[out] = static_cast<float>(std::log(mean_opacity / (1.0 - mean_opacity)));
    for (std::size_t k = 0; k < stride; ++k) target.sh_rest[out * stride + k] = static_cast<float>(rest[k] / n);
    // Attributes the engine keeps but does not interpret (e.g. Mip-Splatting's filter_3D): the mean.
    for (std::size_t e = 0; e < target.extras.size() && e < source.extras.size(); ++e) {
        double sum = 0.0;
        for (const std::uint32_t m : members) sum += source.extras[e].values[m];
        target.extras[e].values[out] = static_cast<float>(sum / n);
    }
}

void thicken(SplatCloud& cloud, std::size_t index, double ratio) {
    if (!(ratio > 0.0)) return;
    glm::vec3& s = cloud.log_scales[index];
    const float floor = std::max({s.x, s.y, s.z}) + static_cast<float>(std::log(ratio));
    s = glm::max(s, glm::vec3(floor));
}

double mean_median_coverage(const CoverageTable& table, std::span<const std::uint32_t> members, int scale) {
    double sum = 0.0;
    std::size_t counted = 0;
    std::vector<double> seen;
    for (const std::uint32_t m : members) {
        seen.clear();
        for (const float s : table.row(m))
            if (s >= 0.0f) seen.push_back(s);
        if (seen.empty()) continue;
        sum += percentile(seen, 50.0) / scale;
        ++counted;
    }
    return counted == 0 ? 0.0 : sum / static_cast<double>(counted);
}

double enlargement(double size_threshold, double mean_coverage, double max_enlargement) {
    if (!(mean_coverage > 0.0)) return max_enlargement;
    return std::clamp(size_threshold / mean_coverage, 1.0, max_enlargement);
}

void set_coverage_ranges(SplatCloud& cloud, const CoverageTable& table, double low_percentile, double high_percentile) {
    if (table.gaussians() != cloud.size()) engine::fail("bake: coverage table and scene differ in size");
    std::vector<double> seen;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const int scale = level_scale(cloud.lod_level[i]);
        seen.clear();
        for (const float s : table.row(i))
            if (s >= 0.0f) seen.push_back(static_cast<double>(s) / scale);
        if (seen.empty()) {
            cloud.coverage_min[i] = cloud.coverage_max[i] = -1.0f;
            continue;
        }
        cloud.coverage_min[i] = static_cast<float>(percentile(seen, low_percentile));
        cloud.coverage_max[i] = static_cast<float>(percentile(seen, high_percentile));
    }
}

double member_cap(std::span<const float> coarse, const std::vector<std::span<const float>>& members,
                  std::span<const float> member_min, const BakeOptions& options) {
    std::vector<double> ratios, sizes;
    for (std::size_t j = 0; j < coarse.size(); ++j) {
        if (!(coarse[j] > 0.0f)) continue;
        sizes.clear();
        for (const auto& row : members)
            if (row[j] > 0.0f) sizes.push_back(row[j]);
        if (!sizes.empty()) ratios.push_back(coarse[j] / percentile(sizes, 50.0));
    }
    if (ratios.empty()) return -1.0;
    std::vector<double> drop;
    for (const float m : member_min)
        drop.push_back(
            std::max(double(options.rule.size_threshold_px), m > 0.0f ? double(options.rule.rel_min) * m : 0.0));
    return percentile(ratios, 50.0) * percentile(drop, 50.0) / double(options.rule.rel_max);
}

void cap_coverage_max(SplatCloud& cloud, const CoverageTable& table, const std::vector<LevelMembers>& levels,
                      const BakeOptions& options) {
    if (table.gaussians() != cloud.size()) engine::fail("bake: coverage table and scene differ in size");
    for (const LevelMembers& level : levels) {
        const std::size_t groups = level.starts.empty() ? 0 : level.starts.size() - 1;
        reference::detail::parallel_for(
            groups, reference::detail::resolve_thread_count(options.threads), [&](std::size_t g) {
                const std::size_t coarse = level.first + g;
                if (!(cloud.coverage_max[coarse] > 0.0f)) return;
                std::vector<std::span<const float>> rows;
                std::vector<float> minima;
                for (std::size_t k = level.starts[g]; k < level.starts[g + 1]; ++k) {
                    rows.push_back(table.row(level.members[k]));
                    minima.push_back(cloud.coverage_min[level.members[k]]);
                }
                const double cap = member_cap(table.row(coarse), rows, minima, options);
                if (cap > 0.0)
                    cloud.coverage_max[coarse] = std::min(cloud.coverage_max[coarse], static_cast<float>(cap));
            });
    }
}

std::vector<std::uint32_t> output_order(const SplatCloud& cloud, const Normaliser& normaliser) {
    std::vector<std::uint64_t> morton(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const glm::dvec3 x = normaliser.apply(glm::dvec3(cloud.positions[i]));
        std::uint64_t code = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const double t = std::clamp((x[axis] + 2.0) / 4.0, 0.0, 1.0) * double((1 << 21) - 1);
            code |= spread_bits(static_cast<std::uint64_t>(t)) << axis;
        }
        morton[i] = code;
    }
    // Size class: log2 of the extent that bounds a Gaussian's coverage (see build_clusters in
    // gpu/gpu_scene.cpp); unseen Gaussians (no range) in a class of their own, last.
    std::vector<int> size_class(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        glm::vec3 s = cloud.log_scales[i];
        std::sort(&s.x, &s.x + 3);
        const double log_extent = std::min(static_cast<double>(s.z), 0.5 * std::log(2.0) + s.y);
        size_class[i] =
            cloud.coverage_min[i] > 0.0f ? static_cast<int>(std::floor(log_extent / std::log(2.0))) : 1 << 20;
    }
    std::vector<std::uint32_t> order(cloud.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        if (cloud.lod_level[a] != cloud.lod_level[b]) return cloud.lod_level[a] > cloud.lod_level[b];
        if (size_class[a] != size_class[b]) return size_class[a] < size_class[b];
        return morton[a] < morton[b];
    });
    return order;
}

reference::ReferenceCamera scaled_camera(const reference::ReferenceCamera& camera, int k) {
    reference::ReferenceCamera scaled = camera;
    scaled.fx /= k;
    scaled.fy /= k;
    scaled.cx /= k;
    scaled.cy /= k;
    scaled.width = camera.width / k;
    scaled.height = camera.height / k;
    return scaled;
}

std::vector<std::size_t> refinement_cameras(const std::vector<reference::ReferenceCamera>& cameras, int limit) {
    std::vector<std::size_t> usable;
    for (std::size_t i = 0; i < cameras.size(); ++i) {
        const auto& c = cameras[i];
        if (c.width % 64 != 0 || c.height % 64 != 0) continue;
        if (!usable.empty()) {
            const auto& first = cameras[usable.front()];
            if (c.fx != first.fx || c.fy != first.fy || c.width != first.width || c.height != first.height) continue;
        }
        usable.push_back(i);
    }
    if (limit <= 0 || usable.size() <= static_cast<std::size_t>(limit)) return usable;
    std::vector<std::size_t> spread;
    for (int j = 0; j < limit; ++j)
        spread.push_back(usable[static_cast<std::size_t>(j) * usable.size() / static_cast<std::size_t>(limit)]);
    return spread;
}

}  // namespace splat_lod::bake::detail
