// Step 3, before binning: turns the key total (on the GPU) into the clamped sort count, the
// overflow flag and the indirect dispatch size of the tile-range pass, without a CPU read-back. The
// frame's statistics add the pairs up (counters cleared at the frame's start, SplatPass).
#include "common_splat_bindings.glsl"

layout(local_size_x = 1) in;
layout(std430, binding = SPLAT_BINDING_CLUSTER_PAIRS) readonly buffer ClusterKeys { uint cluster_keys[]; };
layout(std430, binding = SPLAT_BINDING_STATS) buffer Stats { FrameCounters stats; };
// x, y, z: dispatch size of splat_tile_ranges; w: the number of keys to sort and use.
layout(std430, binding = SPLAT_BINDING_ARGS) writeonly buffer Args { uvec4 args; };

void main() {
    uint clusters = (frame.gaussian_count + SPLAT_PROJECT_WORKGROUP_SIZE - 1u) / SPLAT_PROJECT_WORKGROUP_SIZE;
    uint total = cluster_keys[clusters];
    uint used = min(total, frame.key_capacity);
    stats.keys_needed += total;  // in strips, summed over the frame's strips
    stats.overflowed = max(stats.overflowed, total > frame.key_capacity ? 1u : 0u);
    args = uvec4((used + SPLAT_RANGES_WORKGROUP_SIZE - 1u) / SPLAT_RANGES_WORKGROUP_SIZE, 1u, 1u, used);
}
