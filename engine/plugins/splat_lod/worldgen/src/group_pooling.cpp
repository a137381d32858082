// The pooling of one chunk group, member by member (group_pooling.h; the rule is in world_groups.h).
#include "group_pooling.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <glm/gtc/quaternion.hpp>

#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/splat_math.h"

namespace splat_lod::world {
namespace {

using reference::detail::sigmoid;

// Mean over the three axis projections of √det of the 2×2 block: how much area the Gaussian covers,
// independent of the view (the weight and the opacity scale of the pooling).
double projected_area(const glm::dmat3& s) {
    const double xy = s[0][0] * s[1][1] - s[1][0] * s[1][0];
    const double xz = s[0][0] * s[2][2] - s[2][0] * s[2][0];
    const double yz = s[1][1] * s[2][2] - s[2][1] * s[2][1];
    return (std::sqrt(std::max(xy, 0.0)) + std::sqrt(std::max(xz, 0.0)) + std::sqrt(std::max(yz, 0.0))) / 3.0;
}

struct Activated {
    glm::dvec3 mean{0.0};
    glm::dmat3 covariance{0.0};
    double opacity = 0.0;
    double area = 0.0;
};

Activated activate(const SplatCloud& c, std::size_t i) {
    Activated a;
    a.mean = glm::dvec3(c.positions[i]);
    const glm::dvec3 s = glm::exp(glm::dvec3(c.log_scales[i]));
    const glm::dmat3 rs = math::rotation_of(c.rotations[i]) * glm::dmat3(s.x, 0, 0, 0, s.y, 0, 0, 0, s.z);
    a.covariance = rs * glm::transpose(rs);
    a.opacity = sigmoid(c.opacity_logits[i]);
    a.area = std::max(projected_area(a.covariance), 1e-30);
    return a;
}

bool drawable(const SplatCloud& c, std::size_t i) {
    const glm::vec3& p = c.positions[i];
    const glm::vec3& s = c.log_scales[i];
    const Rotation& q = c.rotations[i];
    const float sum = p.x + p.y + p.z + s.x + s.y + s.z + c.opacity_logits[i] + q.w + q.x + q.y + q.z;
    if (!std::isfinite(sum) || q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z == 0.0f) return false;
    return sigmoid(c.opacity_logits[i]) > 1.0 / 255.0;
}

void copy_gaussian(const SplatCloud& from, std::size_t i, SplatCloud& to, std::size_t out) {
    to.positions[out] = from.positions[i];
    to.rotations[out] = from.rotations[i];
    to.log_scales[out] = from.log_scales[i];
    to.opacity_logits[out] = from.opacity_logits[i];
    to.sh_dc[out] = from.sh_dc[i];
    const std::size_t from_stride = from.sh_rest_stride(), to_stride = to.sh_rest_stride();
    for (std::size_t k = 0; k < std::min(from_stride, to_stride); ++k)
        to.sh_rest[out * to_stride + k] = from.sh_rest[i * from_stride + k];
}

}  // namespace

std::size_t GroupPooling::IndexHash::operator()(const glm::i64vec3& c) const {
    const auto mix = [](std::uint64_t h, std::int64_t v) {
        return (h ^ static_cast<std::uint64_t>(v)) * 0x100000001b3ull;  // FNV-1a, a word at a time
    };
    return static_cast<std::size_t>(mix(mix(mix(0xcbf29ce484222325ull, c.x), c.y), c.z));
}

GroupPooling::GroupPooling(const glm::dvec3& origin, double cell_m) : origin_(origin), cell_m_(cell_m) {
    kept_.set_sh_degree(3);  // copied on into the output's degree, which is known after the first pass
}

void GroupPooling::each_entry(const SplatCloud& c, const std::function<void(std::size_t, std::uint32_t, bool)>& visit) {
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (c.lod_level[i] != 1 || !drawable(c, i)) continue;
        const glm::i64vec3 index(glm::floor((glm::dvec3(c.positions[i]) - origin_) / cell_m_));
        const auto [at, added] = slots_.try_emplace(index, static_cast<std::uint32_t>(cells_.size()));
        if (added) {
            cells_.emplace_back();
            cells_.back().index = index;
        }
        const glm::vec3& s = c.log_scales[i];
        visit(i, at->second, std::exp(static_cast<double>(std::max({s.x, s.y, s.z}))) >= cell_m_);
    }
}

void GroupPooling::first_pass(const SplatCloud& c) {
    degree_ = std::max(degree_, c.sh_degree);
    each_entry(c, [&](std::size_t i, std::uint32_t slot, bool keep) {
        Cell& cell = cells_[slot];
        if (keep) {
            const std::size_t n = kept_.size();
            kept_.resize(n + 1);
            copy_gaussian(c, i, kept_, n);
            cell.kept.push_back(static_cast<std::uint32_t>(n));
            return;
        }
        const Activated a = activate(c, i);
        const double w = a.opacity * a.area;
        cell.total += w;
        cell.mean += w * a.mean;
        ++cell.pooled;
        pooled_cell_.push_back(slot);
        pooled_weight_.push_back(w);
    });
}

void GroupPooling::second_pass(const SplatCloud& c) {
    if (second_ == 0) {  // the first pass is complete: the means and the SH stride are known
        const std::size_t stride = static_cast<std::size_t>(3 * sh_rest_coeffs(degree_));
        for (Cell& cell : cells_) {
            if (cell.pooled > 0) cell.mean /= cell.total;
            cell.rest.assign(stride, 0.0);
        }
    }
    each_entry(c, [&](std::size_t i, std::uint32_t slot, bool keep) {
        if (keep) return;
        Cell& cell = cells_[slot];
        const Activated a = activate(c, i);
        const double w = pooled_weight_[second_++] / cell.total;
        const glm::dvec3 d = a.mean - cell.mean;
        cell.covariance += w * (a.covariance + glm::outerProduct(d, d));
        cell.dc += w * glm::dvec3(c.sh_dc[i]);
        const std::size_t member_stride = c.sh_rest_stride();
        for (std::size_t j = 0; j < std::min(cell.rest.size(), member_stride); ++j)
            cell.rest[j] += w * c.sh_rest[i * member_stride + j];
    });
}

void GroupPooling::write_pooled(const Cell& cell, const glm::dvec3& values, const glm::dmat3& vectors, SplatCloud& to,
                                std::size_t out) const {
    const double opacity = std::clamp(1.0 - std::exp(cell.log_transmittance), 1.01 / 255.0, 0.99);
    const glm::dquat q = glm::normalize(glm::quat_cast(vectors));
    to.positions[out] = glm::vec3(cell.mean);
    to.rotations[out] = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
                         static_cast<float>(q.z)};
    for (int axis = 0; axis < 3; ++axis)
        to.log_scales[out][axis] = static_cast<float>(0.5 * std::log(std::max(values[axis], 1e-30)));
    to.opacity_logits[out] = static_cast<float>(std::log(opacity / (1.0 - opacity)));
    to.sh_dc[out] = glm::vec3(cell.dc);
    const std::size_t stride = to.sh_rest_stride();
    for (std::size_t j = 0; j < stride; ++j) to.sh_rest[out * stride + j] = static_cast<float>(cell.rest[j]);
}

SplatCloud GroupPooling::finish(double fill) {
    // The pooled Gaussian's axes (widened), and its area, which the opacity's product needs.
    std::vector<glm::dvec3> values(cells_.size());
    std::vector<glm::dmat3> vectors(cells_.size());
    std::vector<double> area(cells_.size(), 0.0);
    for (std::size_t k = 0; k < cells_.size(); ++k) {
        if (cells_[k].pooled == 0) continue;
        math::symmetric_eigen(cells_[k].covariance, values[k], vectors[k]);
        if (glm::determinant(vectors[k]) < 0.0) vectors[k][2] = -vectors[k][2];
        for (int axis = 0; axis < 3; ++axis)
            if (values[k][axis] > 0.01 * cell_m_ * cell_m_) values[k][axis] *= fill * fill;
        const glm::dmat3 widened = vectors[k] * glm::dmat3(values[k].x, 0, 0, 0, values[k].y, 0, 0, 0, values[k].z) *
                                   glm::transpose(vectors[k]);
        area[k] = std::max(projected_area(widened), 1e-30);
    }
    for (std::size_t n = 0; n < pooled_cell_.size(); ++n) {
        Cell& cell = cells_[pooled_cell_[n]];
        cell.log_transmittance += std::log1p(-std::min(0.99, pooled_weight_[n] / area[pooled_cell_[n]]));
    }
    // Cells in Morton order of their offset from the lowest cell (ties, which need 21 bits of
    // offset, by the index itself).
    glm::i64vec3 low = cells_.empty() ? glm::i64vec3(0) : cells_.front().index;
    for (const Cell& cell : cells_) low = glm::min(low, cell.index);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order;  // (Morton code, slot)
    std::size_t outputs = 0;
    for (std::size_t k = 0; k < cells_.size(); ++k) {
        const glm::u64vec3 d(cells_[k].index - low);
        order.emplace_back(math::spread_bits(d.x) | math::spread_bits(d.y) << 1 | math::spread_bits(d.z) << 2,
                           static_cast<std::uint32_t>(k));
        outputs += (cells_[k].pooled > 0 ? 1 : 0) + cells_[k].kept.size();
    }
    std::sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
        if (a.first != b.first) return a.first < b.first;
        const glm::i64vec3 &p = cells_[a.second].index, &q = cells_[b.second].index;
        return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
    });
    SplatCloud out;
    out.set_sh_degree(degree_);
    out.resize(outputs);
    std::size_t next = 0;
    for (const auto& [morton, k] : order) {
        if (cells_[k].pooled > 0) write_pooled(cells_[k], values[k], vectors[k], out, next++);
        for (const std::uint32_t kept : cells_[k].kept) copy_gaussian(kept_, kept, out, next++);
    }
    std::fill(out.lod_level.begin(), out.lod_level.end(), std::uint8_t{4});
    std::fill(out.coverage_min.begin(), out.coverage_min.end(), -1.0f);
    std::fill(out.coverage_max.begin(), out.coverage_max.end(), -1.0f);
    return out;
}

}  // namespace splat_lod::world
