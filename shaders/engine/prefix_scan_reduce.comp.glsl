// Prefix scan, upsweep: the sum of each SCAN_BLOCK_SIZE block of a level becomes one element of
// the next level (scan_sums), which the top level scans and the downsweep adds back.
#include "prefix_scan_common.glsl"

void main() {
    const uint count = scan_levels[u_level].count;
    const uint first = gl_WorkGroupID.x * SCAN_BLOCK_SIZE + gl_LocalInvocationID.x;
    uint sum = 0u;
    // Strided so that neighbouring invocations read neighbouring elements.
    for (uint k = 0u; k < SCAN_ELEMENTS_PER_THREAD; ++k) {
        const uint i = first + k * SCAN_WORKGROUP_SIZE;
        if (i < count) sum += scan_data[u_data_offset + i];
    }
    uint total;
    workgroup_exclusive_scan(sum, total);
    if (gl_LocalInvocationID.x == 0u) scan_sums[u_sums_offset + gl_WorkGroupID.x] = total;
}
