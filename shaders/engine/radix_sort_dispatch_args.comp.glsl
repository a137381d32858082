// Radix sort, arguments: from the element count on the GPU (never read back by the CPU), the
// tile count that sizes every indirect dispatch of the sort and the length of the histogram the
// scan walks, so the work follows the real count rather than the capacity.
#include "gpu_sort_shared.h"

layout(local_size_x = 1) in;

layout(std430, binding = SORT_BINDING_COUNT) readonly buffer SortCount { uint sort_count[]; };
layout(std430, binding = SORT_BINDING_PARAMS) writeonly buffer SortParamsBlock { SortParams sort_params; };

uniform uint u_count_index;  // word index of the count in sort_count
uniform uint u_max_count;    // the capacity: a larger count on the GPU is clamped to it

void main() {
    const uint count = min(sort_count[u_count_index], u_max_count);
    const uint tiles = (count + SORT_TILE_SIZE - 1u) / SORT_TILE_SIZE;
    sort_params.dispatch = uvec4(tiles, 1u, 1u, 0u);
    sort_params.count = count;
    sort_params.tile_count = tiles;
    sort_params.histogram_count = tiles * SORT_RADIX_SIZE;
    sort_params.histogram_total = 0u;
}
