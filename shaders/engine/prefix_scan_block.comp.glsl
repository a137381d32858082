// Prefix scan, per block: an exclusive scan of SCAN_BLOCK_SIZE elements in place, plus the
// block's offset from the scanned next level (downsweep), or writing the grand total (top level,
// a single workgroup).
#include "prefix_scan_common.glsl"

layout(std430, binding = SCAN_BINDING_TOTAL) buffer ScanTotal { uint scan_total[]; };

uniform bool u_add_block_offsets;  // false on the top level
uniform bool u_write_total;        // true on the top level
uniform uint u_total_index;        // word index of the total in scan_total

void main() {
    const uint count = scan_levels[u_level].count;
    const uint lid = gl_LocalInvocationID.x;
    // Blocked: each invocation owns consecutive elements, so its sequential sum keeps the order.
    const uint first = gl_WorkGroupID.x * SCAN_BLOCK_SIZE + lid * SCAN_ELEMENTS_PER_THREAD;
    uint values[SCAN_ELEMENTS_PER_THREAD];
    uint sum = 0u;
    for (uint k = 0u; k < SCAN_ELEMENTS_PER_THREAD; ++k) {
        const uint i = first + k;
        values[k] = i < count ? scan_data[u_data_offset + i] : 0u;
        sum += values[k];
    }
    uint total;
    uint prefix = workgroup_exclusive_scan(sum, total);
    if (u_add_block_offsets) prefix += scan_sums[u_sums_offset + gl_WorkGroupID.x];
    for (uint k = 0u; k < SCAN_ELEMENTS_PER_THREAD; ++k) {
        const uint i = first + k;
        if (i < count) scan_data[u_data_offset + i] = prefix;
        prefix += values[k];
    }
    if (u_write_total && lid == 0u) scan_total[u_total_index] = total;
}
