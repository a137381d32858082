#pragma once
// Internal to the bake (docs/algorithms.md §4): steps 2–3, the normalised positions and the cells that the
// Gaussians small at a level pool by.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "coverage.h"
#include "splat_lod/core/splat_math.h"

namespace splat_lod::bake::detail {

using math::rotation_of;
using math::spread_bits;
using math::symmetric_eigen;

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

// The members of one coarse level's Gaussians: Gaussian first + g pooled
// members[starts[g] .. starts[g + 1]) (indices into the cloud).
struct LevelMembers {
    std::size_t first = 0;
    std::vector<std::uint32_t> members;
    std::vector<std::size_t> starts;
};

// Steps 1–3 for one level: the Gaussians of finer levels that some camera sees smaller than S_T at
// the level's scale, by cell. Cell g's members are members[starts[g] .. starts[g + 1]) (first unset).
LevelMembers small_by_cell(const SplatCloud& cloud, const CoverageTable& table, int level, const Normaliser& normaliser,
                           const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options,
                           LevelSummary& summary);

}  // namespace splat_lod::bake::detail
