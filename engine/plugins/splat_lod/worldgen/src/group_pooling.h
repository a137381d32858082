#pragma once
// The pooling of one chunk group (world_groups.h: the cells, the moments, the fill), done while the
// group's members stream by one at a time, so that a group of the whole world needs no more memory
// than one member's cloud and the sums of its cells.
//
// Two passes over the members in order: the first finds each level-1 Gaussian's cell, adds its weight
// and weighted mean to the cell, keeps a copy of the Gaussians larger than a cell and notes each
// pooled weight (12 bytes a Gaussian); the second adds the spread about each cell's mean and the
// colour. Every sum runs over a cell's members in member and file order, as one pass over all members
// in memory would, so the output is the same bytes however the members are read.
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::world {

class GroupPooling {
public:
    GroupPooling(const glm::dvec3& origin, double cell_m);
    // Every member, in order, first to first_pass(), then to second_pass(), then finish() once.
    void first_pass(const SplatCloud& member);
    void second_pass(const SplatCloud& member);
    // The group's Gaussians in Morton order of the cells: a cell's pooled Gaussian (spread axes
    // widened by `fill`), then its Gaussians larger than a cell, in member and file order.
    SplatCloud finish(double fill);

private:
    struct Cell {
        glm::i64vec3 index{0};
        std::size_t pooled = 0;  // level-1 Gaussians pooled into it
        double total = 0.0;      // Σ w
        glm::dvec3 mean{0.0};
        glm::dmat3 covariance{0.0};
        glm::dvec3 dc{0.0};
        std::vector<double> rest;
        double log_transmittance = 0.0;
        std::vector<std::uint32_t> kept;  // into kept_
    };
    struct IndexHash {
        std::size_t operator()(const glm::i64vec3& c) const;
    };
    // Calls visit(i, cell, keep) for each drawable level-1 Gaussian i of `member`.
    void each_entry(const SplatCloud& member, const std::function<void(std::size_t, std::uint32_t, bool)>& visit);
    void write_pooled(const Cell& cell, const glm::dvec3& values, const glm::dmat3& vectors, SplatCloud& to,
                      std::size_t out) const;

    glm::dvec3 origin_;
    double cell_m_;
    int degree_ = 0;
    std::unordered_map<glm::i64vec3, std::uint32_t, IndexHash> slots_;
    std::vector<Cell> cells_;
    std::vector<std::uint32_t> pooled_cell_;  // per pooled Gaussian of the first pass, in order
    std::vector<double> pooled_weight_;       // its w = α·A
    SplatCloud kept_;
    std::size_t second_ = 0;  // pooled Gaussians seen by the second pass
};

}  // namespace splat_lod::world
