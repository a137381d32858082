// Prefix scan, arguments: from the element count on the GPU (never read back by the CPU), the
// element count and workgroup count of every level, so each indirect dispatch scales with the
// real count rather than the capacity.
#include "gpu_sort_shared.h"

layout(local_size_x = 1) in;

layout(std430, binding = SCAN_BINDING_COUNT) readonly buffer ScanCount { uint scan_count[]; };
layout(std430, binding = SCAN_BINDING_LEVELS) writeonly buffer ScanLevels { ScanLevel scan_levels[SCAN_MAX_LEVELS]; };

uniform uint u_count_index;  // word index of the count in scan_count
uniform uint u_max_count;    // the capacity: a larger count on the GPU is clamped to it

void main() {
    uint count = min(scan_count[u_count_index], u_max_count);
    for (uint level = 0u; level < SCAN_MAX_LEVELS; ++level) {
        const uint groups = (count + SCAN_BLOCK_SIZE - 1u) / SCAN_BLOCK_SIZE;
        scan_levels[level] = ScanLevel(groups, 1u, 1u, count);
        count = groups;
    }
}
