// Shared by the prefix scan stages: the level buffers and a workgroup-wide exclusive scan that
// needs no subgroup operations (llvmpipe lacks some), only shared memory and four barriers.
#include "gpu_sort_shared.h"

layout(local_size_x = SCAN_WORKGROUP_SIZE) in;

layout(std430, binding = SCAN_BINDING_DATA) buffer ScanData { uint scan_data[]; };
layout(std430, binding = SCAN_BINDING_SUMS) buffer ScanSums { uint scan_sums[]; };
layout(std430, binding = SCAN_BINDING_LEVELS) readonly buffer ScanLevels { ScanLevel scan_levels[SCAN_MAX_LEVELS]; };

uniform uint u_level;        // index into scan_levels
uniform uint u_data_offset;  // first element of this level in scan_data
uniform uint u_sums_offset;  // first block sum of this level in scan_sums

// 32 rakers each scan a run of this many values sequentially, then one invocation scans the 32
// run totals: fewer barriers than a log-step scan, which matters where barriers are costly.
#define SCAN_RAKE_RUN (SCAN_WORKGROUP_SIZE / 32)

shared uint s_scan[SCAN_WORKGROUP_SIZE];
shared uint s_rake[32];
shared uint s_scan_total;

// Exclusive prefix of `value` over the workgroup in invocation order; `total` is the sum of all.
uint workgroup_exclusive_scan(uint value, out uint total) {
    const uint lid = gl_LocalInvocationID.x;
    s_scan[lid] = value;
    barrier();
    if (lid < 32u) {
        uint sum = 0u;
        for (uint k = 0u; k < SCAN_RAKE_RUN; ++k) {
            const uint v = s_scan[lid * SCAN_RAKE_RUN + k];
            s_scan[lid * SCAN_RAKE_RUN + k] = sum;
            sum += v;
        }
        s_rake[lid] = sum;
    }
    barrier();
    if (lid == 0u) {
        uint sum = 0u;
        for (uint k = 0u; k < 32u; ++k) {
            const uint v = s_rake[k];
            s_rake[k] = sum;
            sum += v;
        }
        s_scan_total = sum;
    }
    barrier();
    const uint prefix = s_scan[lid] + s_rake[lid / SCAN_RAKE_RUN];
    total = s_scan_total;
    barrier();  // the caller may scan again: nobody may still be reading s_scan
    return prefix;
}
