// The survey of a capture and the world frame chosen from it (capture_survey.h, world_import.h).
#include "capture_survey.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "engine/core/error.h"
#include "splat_lod/core/chunk_quadtree.h"
#include "splat_lod/core/cloud_transform.h"
#include "splat_lod/core/gaussian_extent.h"
#include "splat_lod/core/splat_math.h"

namespace splat_lod::world {
namespace {

constexpr double kSnapDegrees = 5.0;
// The thinnest axis of the centres is a weaker estimate (trees and houses placed at random tilt it):
// within this angle of a coordinate axis it is taken to be that axis, as captures mostly are aligned.
constexpr double kWeakSnapDegrees = 30.0;
constexpr double kFlatRatio = 0.25;   // smallest scale below this fraction of the middle one
constexpr double kFlatOpacity = 0.5;  // and at least this opaque: a surface element
// The flat Gaussians' normals give up only when one direction dominates them: their moment matrix's
// largest eigenvalue at least this many times the next (a ground, roofs, a road). Scenes of leaves,
// walls and clutter spread their normals, and the thinnest axis of the centres says more.
constexpr double kDominantNormal = 1.5;
constexpr std::uint64_t kMinFlat = 100;
// An aerial capture is flat (height span below this share of the footprint) and made of coarse
// Gaussians (median extent above this share of the footprint): measured, the 4.2M aerial capture of
// docs/results.md spans 4.8 % in height with a median extent of 3.7e-4 of its footprint, the generated
// world (seen from eye height, centimetre leaves) 1.6 % and 1.3e-4. Height alone cannot tell them apart.
constexpr double kAerialFlatness = 0.06;
constexpr double kAerialCoarseness = 2.5e-4;
constexpr double kHugeTimesMedian = 64.0;

void add_flat_normal(const SplatCloud& cloud, std::size_t i, CaptureSample& sample) {
    glm::vec3 s = cloud.log_scales[i];
    int smallest = 0;
    for (int k = 1; k < 3; ++k)
        if (s[k] < s[smallest]) smallest = k;
    const float middle = std::min(s[(smallest + 1) % 3], s[(smallest + 2) % 3]);
    if (!(std::exp(static_cast<double>(s[smallest]) - static_cast<double>(middle)) < kFlatRatio)) return;
    if (!(opacity_from_logit(cloud.opacity_logits[i]) >= kFlatOpacity)) return;
    const glm::dvec3 n = math::rotation_of(cloud.rotations[i])[smallest];
    sample.normal_moments += glm::outerProduct(n, n);
    ++sample.flat;
}

void thin_sample(CaptureSample& sample) {
    std::vector<glm::vec3> kept;
    kept.reserve(sample.positions.size() / 2 + 1);
    for (std::size_t i = 0; i < sample.positions.size(); i += 2) kept.push_back(sample.positions[i]);
    sample.positions = std::move(kept);
    sample.stride *= 2;
}

double percentile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    const auto k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return values[k];
}

std::vector<double> along(const std::vector<glm::vec3>& points, const glm::dvec3& axis) {
    std::vector<double> out;
    out.reserve(points.size());
    for (const glm::vec3& p : points) out.push_back(glm::dot(glm::dvec3(p), axis));
    return out;
}

// The up axis before its sign: the dominant normal of flat Gaussians, else the positions' thinnest axis.
glm::dvec3 up_axis(const CaptureSample& sample, std::string& source, double& snap_degrees) {
    snap_degrees = kSnapDegrees;
    glm::dvec3 values;
    glm::dmat3 vectors;
    std::string ambiguous;
    if (sample.flat >= kMinFlat) {
        math::symmetric_eigen(sample.normal_moments, values, vectors);
        int order[3] = {0, 1, 2};
        std::sort(order, order + 3, [&](int a, int b) { return values[a] > values[b]; });
        char ratio[64];
        std::snprintf(ratio, sizeof ratio, "%.2f", values[order[0]] / std::max(values[order[1]], 1e-300));
        if (values[order[0]] >= kDominantNormal * values[order[1]]) {
            source = "flat Gaussians (" + std::to_string(sample.flat) + ", dominant normal " + ratio + "x the next)";
            return vectors[order[0]];
        }
        ambiguous = "; the flat Gaussians' normals are ambiguous (dominant only " + std::string(ratio) + "x the next)";
    }
    glm::dvec3 mean(0.0);
    for (const glm::vec3& p : sample.positions) mean += glm::dvec3(p);
    mean /= static_cast<double>(sample.positions.size());
    glm::dmat3 covariance(0.0);
    for (const glm::vec3& p : sample.positions)
        covariance += glm::outerProduct(glm::dvec3(p) - mean, glm::dvec3(p) - mean);
    math::symmetric_eigen(covariance, values, vectors);
    int thinnest = 0;
    for (int k = 1; k < 3; ++k)
        if (values[k] < values[thinnest]) thinnest = k;
    source = "thinnest axis of the centres" + ambiguous;
    snap_degrees = kWeakSnapDegrees;
    return vectors[thinnest];
}

// Towards the longer tail of heights (what stands on the ground), snapped to a nearby coordinate axis.
glm::dvec3 orient_up(glm::dvec3 up, const CaptureSample& sample, double snap_degrees) {
    up = glm::normalize(up);
    const std::vector<double> heights = along(sample.positions, up);
    const double low = percentile(heights, 0.01), mid = percentile(heights, 0.5), high = percentile(heights, 0.99);
    if (high - mid < mid - low) up = -up;
    for (int k = 0; k < 3; ++k) {
        glm::dvec3 axis(0.0);
        axis[k] = up[k] < 0.0 ? -1.0 : 1.0;
        if (glm::dot(up, axis) >= std::cos(snap_degrees * 3.14159265358979 / 180.0)) return axis;
    }
    return up;
}

struct Box2 {
    double x_lo, x_hi, z_lo, z_hi;
};

// The largest power-of-two chunk (relative to the footprint's power of two) at which no cell of the
// sample holds more than the cap, with at most kMaxChunksPerSide chunks per side (a capture denser than
// that gets fuller chunks); the translation snapped to that chunk.
void choose_chunks(const std::vector<glm::vec3>& world, const Box2& box, std::uint64_t stride, std::uint64_t cap,
                   CaptureFrame& frame) {
    const double footprint = std::max(box.x_hi - box.x_lo, box.z_hi - box.z_lo);
    const double top = std::exp2(std::ceil(std::log2(footprint)));
    const glm::dvec2 centre(0.5 * (box.x_lo + box.x_hi), 0.5 * (box.z_lo + box.z_hi));
    for (int k = 0; k <= 16; ++k) {
        const double c = top / std::exp2(k);
        const glm::dvec2 shift = -glm::round(centre / c) * c;
        std::map<std::pair<long long, long long>, std::uint64_t> counts;
        std::uint64_t most = 0;
        for (const glm::vec3& p : world) {
            if (p.x < box.x_lo || p.x > box.x_hi || p.z < box.z_lo || p.z > box.z_hi) continue;
            const auto key = std::make_pair(static_cast<long long>(std::floor((p.x + shift.x) / c)),
                                            static_cast<long long>(std::floor((p.z + shift.y) / c)));
            most = std::max(most, counts[key] += stride);
        }
        const double reach = std::max({std::fabs(box.x_lo + shift.x), std::fabs(box.x_hi + shift.x),
                                       std::fabs(box.z_lo + shift.y), std::fabs(box.z_hi + shift.y)});
        const int per_side = std::max(2, 2 * static_cast<int>(std::ceil(reach / c)));
        const bool finer_fits = k < 16 && 2 * per_side + 2 <= kMaxChunksPerSide;
        if (most > cap && finer_fits) continue;
        frame.chunk_size = static_cast<float>(c);
        frame.chunks_per_side = per_side;
        frame.translation.x += shift.x;
        frame.translation.z += shift.y;
        return;
    }
}

// The quadtree's spans (CaptureFrame::spans), bottom-up: a square of 2^s × 2^s cells inside the grid is
// one chunk when its four quarters are and its sample estimate is at most the densest cell's (never above
// the cap), so that no merged chunk is fuller than the grid already has one; at most span D − 1 for a grid
// of D group depths, so that a group stays above every chunk.
void choose_spans(const std::vector<glm::vec3>& world, std::uint64_t stride, std::uint64_t cap, CaptureFrame& frame) {
    const int n = frame.chunks_per_side;
    std::vector<std::uint64_t> counts(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0);
    for (const glm::vec3& p : world) {
        const glm::ivec2 i(static_cast<int>(std::floor((p.x + frame.translation.x) / frame.chunk_size)) + n / 2,
                           static_cast<int>(std::floor((p.z + frame.translation.z) / frame.chunk_size)) + n / 2);
        if (i.x >= 0 && i.y >= 0 && i.x < n && i.y < n) counts[static_cast<std::size_t>(i.y * n + i.x)] += stride;
    }
    frame.spans.assign(counts.size(), 0);
    const std::uint64_t fullest = std::min(cap, *std::max_element(counts.begin(), counts.end()));
    std::vector<std::uint64_t> sums = counts;  // at span s: the square's estimate (cells at its lowest corner)
    std::vector<std::uint8_t> whole(counts.size(), 1);
    for (int s = 1; s < group_depths(n); ++s) {
        const int side = 1 << s, half = side / 2;
        bool any = false;
        for (int z = 0; z + side <= n; z += side)
            for (int x = 0; x + side <= n; x += side) {
                const auto at = [&](int dx, int dz) { return static_cast<std::size_t>((z + dz) * n + x + dx); };
                const std::uint64_t sum = sums[at(0, 0)] + sums[at(half, 0)] + sums[at(0, half)] + sums[at(half, half)];
                const bool merge = whole[at(0, 0)] && whole[at(half, 0)] && whole[at(0, half)] &&
                                   whole[at(half, half)] && sum <= fullest;
                sums[at(0, 0)] = sum;
                whole[at(0, 0)] = merge ? 1 : 0;
                if (!merge) continue;
                any = true;
                for (int dz = 0; dz < side; ++dz)
                    for (int dx = 0; dx < side; ++dx) frame.spans[at(dx, dz)] = static_cast<std::uint8_t>(s);
            }
        if (!any) break;  // no square of this span is whole, so none larger is
    }
}

}  // namespace

glm::ivec2 CaptureFrame::chunk_of(const glm::ivec2& cell, int& span) const {
    const int n = chunks_per_side;
    const glm::ivec2 i = cell + glm::ivec2(n / 2);
    span = spans.empty() ? 0 : spans[static_cast<std::size_t>(i.y * n + i.x)];
    const int side = 1 << span;
    return (i / side) * side - glm::ivec2(n / 2);
}

CaptureSample survey_capture(const Capture& capture, std::uint64_t sample_max,
                             const std::function<void(std::uint64_t)>& progress) {
    CaptureSample sample;
    std::uint64_t index = 0;
    std::vector<double> extents;
    for (std::size_t p = 0; p < capture.parts.size(); ++p) {
        LoadReport report;
        const SplatCloud part = read_capture_part(capture.parts[p], &report);
        sample.read += part.size();
        sample.dropped_by_reader += report.dropped();
        sample.sh_degree = std::max(sample.sh_degree, part.sh_degree);
        for (std::size_t i = 0; i < part.size(); ++i) {
            const double extent = gaussian_extent(part.log_scales[i], part.opacity_logits[i]);
            if (!(extent > 0.0)) {
                ++sample.invisible;
                continue;
            }
            add_flat_normal(part, i, sample);
            if (index++ % sample.stride != 0) continue;
            sample.positions.push_back(part.positions[i]);
            if (extents.size() < sample_max) extents.push_back(extent);
            if (sample.positions.size() >= 2 * sample_max) thin_sample(sample);
        }
        if (progress) progress(p + 1);
    }
    sample.median_extent = percentile(extents, 0.5);
    return sample;
}

bool CaptureFrame::cell_of(const glm::vec3& p, glm::ivec2& cell) const {
    const float half = 0.5f * size();
    if (!(p.x >= -half && p.x < half && p.z >= -half && p.z < half && p.y >= height_lo && p.y <= height_hi))
        return false;
    cell = glm::ivec2(static_cast<int>(std::floor(p.x / chunk_size)), static_cast<int>(std::floor(p.z / chunk_size)));
    cell = glm::clamp(cell, glm::ivec2(-chunks_per_side / 2), glm::ivec2(chunks_per_side / 2 - 1));
    return true;
}

CaptureFrame choose_frame(const CaptureSample& sample, const ImportOptions& o, const std::string& name) {
    if (sample.positions.empty())
        engine::fail(name + ": no visible Gaussian is left (" + std::to_string(sample.read) + " read, " +
                     std::to_string(sample.invisible) + " never visible)");
    CaptureFrame frame;
    if (o.up) {
        frame.up = glm::normalize(glm::dvec3(*o.up));
        frame.up_source = "given";
    } else {
        double snap_degrees = kSnapDegrees;
        const glm::dvec3 axis = up_axis(sample, frame.up_source, snap_degrees);
        frame.up = orient_up(axis, sample, snap_degrees);
    }
    frame.rotation = rotation_between(frame.up, glm::dvec3(0.0, 1.0, 0.0));
    std::vector<glm::vec3> world;
    world.reserve(sample.positions.size());
    for (const glm::vec3& p : sample.positions) world.push_back(glm::vec3(frame.rotation * glm::dvec3(p)));
    const auto xs = along(world, {1, 0, 0}), ys = along(world, {0, 1, 0}), zs = along(world, {0, 0, 1});
    const Box2 box{percentile(xs, 0.01), percentile(xs, 0.99), percentile(zs, 0.01), percentile(zs, 0.99)};
    const double footprint = std::max(box.x_hi - box.x_lo, box.z_hi - box.z_lo);
    if (!(footprint > 0.0) || !std::isfinite(footprint))
        engine::fail(name +
                     ": the Gaussians' centres have no horizontal extent (all at one point or on one line "
                     "across the up axis): nothing to cut into chunks");
    frame.footprint = static_cast<float>(footprint);
    const double y_lo = percentile(ys, 0.01), y_hi = percentile(ys, 0.99);
    frame.height_span = static_cast<float>(y_hi - y_lo);
    frame.height_lo = static_cast<float>(y_lo - footprint);
    frame.height_hi = static_cast<float>(y_hi + footprint);
    frame.degenerate_extent = static_cast<float>(1e-7 * footprint);
    frame.aerial = o.views == CaptureViews::aerial ||
                   (o.views == CaptureViews::automatic && y_hi - y_lo < kAerialFlatness * footprint &&
                    sample.median_extent > kAerialCoarseness * footprint);
    choose_chunks(world, box, sample.stride, o.max_chunk_gaussians, frame);
    if (o.quadtree) choose_spans(world, sample.stride, o.max_chunk_gaussians, frame);
    // Huge: wider than half a chunk (its bounds would grow past its neighbours') and far wider than the
    // capture's typical Gaussian (sky and background are 100–1000× the median; a capture denser than any
    // chunk has small chunks, and its ordinary Gaussians must stay in them).
    frame.huge_extent = static_cast<float>(std::max(0.5 * frame.chunk_size, kHugeTimesMedian * sample.median_extent));
    return frame;
}

}  // namespace splat_lod::world
