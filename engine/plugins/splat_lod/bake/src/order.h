#pragma once
// Internal to the bake (docs/algorithms.md §4): the order of the baked Gaussians in the file.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "cells.h"

namespace splat_lod::bake::detail {

// Output order: coarsest level first; within a level by size class (a factor of 2 in the extent
// that bounds coverage; Gaussians no camera saw last), then along a Morton curve of the normalised
// position (ties by index). A level is a contiguous prefix for streaming, and each run of 256 (a
// project workgroup) holds Gaussians of one size near each other, which the renderer can skip
// together when all are too small for the view (GpuCluster).
std::vector<std::uint32_t> output_order(const SplatCloud& cloud, const Normaliser& normaliser);

}  // namespace splat_lod::bake::detail
