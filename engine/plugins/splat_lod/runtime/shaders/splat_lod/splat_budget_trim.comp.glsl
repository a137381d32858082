// Step 1d, the splat budget's trim: one workgroup per cluster step 1b projected (the same indirect
// dispatch), one invocation per splat it wrote. A splat stays only if it is selected at the β bin
// step 1c chose and its coverage is not below the cut; the others get opacity 0, which gives them no
// tiles, so no later pass sees them. A kept splat's opacity is scaled by its LOD weight at coverage/β
// (smooth transitions), and its tiles are counted again at that opacity: the splats' first keys within
// the cluster and the cluster's pair count (SPLAT_BINDING_CLUSTER_PAIRS) are what step 3 writes. Counts
// the drawn Gaussians per level (step 1b does not, under a budget).
#include "common_splat_bindings.glsl"

layout(local_size_x = SPLAT_PROJECT_WORKGROUP_SIZE) in;
layout(std430, binding = SPLAT_BINDING_PROJECTED) buffer Projected { ProjectedSplat projected[]; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_PAIRS) writeonly buffer ClusterPairs { uint cluster_pairs[]; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_SPLATS) readonly buffer ClusterSplats { uvec2 cluster_splats[]; };
layout(std430, binding = SPLAT_BINDING_STATS) buffer Stats { FrameCounters stats; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_LIST) readonly buffer ClusterList { uvec4 dispatch; uint ids[]; } cluster_list;
layout(std430, binding = SPLAT_BINDING_BUDGET) readonly buffer Budget { SplatBudgetState budget; };
layout(std430, binding = SPLAT_BINDING_INSTANCES) readonly buffer Instances { GpuInstance instances[]; };

#include "common_splat_storage.glsl"
#include "common_splat_lod.glsl"
#include "common_splat_tiles.glsl"
#include "common_splat_cluster_scan.glsl"

// The splat's tiles at the chosen β; 0 when it is not drawn (its opacity then set to 0).
uint trim(uint cluster, uint entry) {
    uint bits = floatBitsToUint(projected[entry].conic.w);
    uint lo = bits & 0xFFu, hi = (bits >> 8) & 0xFFu;
    uint index = cluster * SPLAT_PROJECT_WORKGROUP_SIZE + ((bits >> 16) & 0xFFu);
    uint level = ((bits >> 24) & 0x3u) + 1u;
    float coverage = projected[entry].color.w;
    uint chosen = budget.choice.x, cut = budget.choice.y;
    float opacity = projected[entry].mean_depth.w;
    uint instance = floatBitsToUint(load_gaussian(index).covariance_b.w);
    if (!(lo <= chosen && chosen <= hi && coverage_bin(coverage) >= cut)) {
        opacity = 0.0;
    } else {
        vec3 transition = instance_transition(instances[instance].info.z);
        if (smooth_transitions(transition)) {
            vec4 lod = load_lod(index);
            float beta = chosen == 0u ? 1.0 : exp2(float(chosen) / SPLAT_BUDGET_BINS_PER_OCTAVE);
            opacity *= lod_weight(level, coverage / beta, lod.x, lod.y, transition);
        }
    }
    // The footprint shrinks with the opacity; one that holds no pixel centre any more draws nothing.
    uint tiles = splat_tile_count(projected[entry].mean_depth.xy, projected[entry].conic, opacity);
    projected[entry].mean_depth.w = tiles > 0u ? opacity : 0.0;
    // The coverage is read: the instance takes its place, for picking (ProjectedSplat::color).
    projected[entry].color.w = uintBitsToFloat(SPLAT_BUDGET_PACK_FLAG | instance);
    if (tiles > 0u) {
        atomicAdd(stats.visible, 1u);
        atomicAdd(stats.per_level[level - 1u], 1u);
    }
    return tiles;
}

void main() {
    uint lid = gl_LocalInvocationIndex;
    uint cluster = cluster_list.ids[gl_WorkGroupID.x];
    uvec2 splats = cluster_splats[cluster];
    if (splats.y == 0u) return;  // the whole workgroup
    uint tiles = lid < splats.y ? trim(cluster, splats.x + lid) : 0u;
    scan_cluster(lid, uvec2(0u, tiles));
    if (lid == 0u) cluster_pairs[cluster] = s_scan_total.y;
    barrier();
    if (lid < splats.y)
        projected[splats.x + lid].conic.w = uintBitsToFloat(SPLAT_BUDGET_PACK_FLAG | cluster_prefix(lid).y);
}
