// Step 1d, the splat budget's trim: one invocation per Gaussian of the clusters step 1a kept (the
// same indirect dispatch as step 1b). A splat that step 1b projected stays only if it is selected
// at the β bin step 1c chose and its coverage is not below the cut; the others get 0 tiles, so no
// later pass sees them. A kept splat's opacity is scaled by its LOD weight at coverage/β (smooth
// transitions; step 1b's extent, from the unscaled opacity, stays a conservative bound). Counts the
// drawn Gaussians per level (step 1b does not, under a budget).
#include "common_splat_bindings.glsl"

layout(local_size_x = SPLAT_PROJECT_WORKGROUP_SIZE) in;
layout(std430, binding = SPLAT_BINDING_PROJECTED) buffer Projected { ProjectedSplat projected[]; };
layout(std430, binding = SPLAT_BINDING_TILE_COUNTS) buffer TileCounts { uint tile_counts[]; };
layout(std430, binding = SPLAT_BINDING_STATS) buffer Stats { FrameCounters stats; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_LIST) readonly buffer ClusterList { uvec4 dispatch; uint ids[]; } cluster_list;
layout(std430, binding = SPLAT_BINDING_BUDGET) readonly buffer Budget { SplatBudgetState budget; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_SLOTS) readonly buffer ClusterSlots { uint cluster_slots[]; };

#include "common_splat_storage.glsl"
#include "common_splat_lod.glsl"
#include "common_splat_tiles.glsl"

void main() {
    uint cluster = cluster_list.ids[gl_WorkGroupID.x];
    uint index = cluster * SPLAT_PROJECT_WORKGROUP_SIZE + gl_LocalInvocationIndex;
    uint first = cluster_slots[cluster];
    if (index >= frame.gaussian_count || first == SPLAT_NO_SLOT) return;
    uint slot = first * SPLAT_PROJECT_WORKGROUP_SIZE + gl_LocalInvocationIndex;
    if (tile_counts[slot] == 0u) return;  // culled by step 1b
    uint bits = floatBitsToUint(projected[slot].conic.w);
    uint lo = bits & 0xFFu, hi = (bits >> 8) & 0xFFu, cbin = (bits >> 16) & 0xFFu;
    uint level = ((bits >> 24) & 0x3u) + 1u;
    uint chosen = budget.choice.x, cut = budget.choice.y;
    if (lo <= chosen && chosen <= hi && cbin >= cut) {
        if (smooth_transitions()) {
            vec4 lod = load_lod(index);
            float beta = chosen == 0u ? 1.0 : exp2(float(chosen) / SPLAT_BUDGET_BINS_PER_OCTAVE);
            float opacity = projected[slot].mean_depth.w * lod_weight(level, projected[slot].color.w / beta, lod.x, lod.y);
            if (!(opacity > 1.0 / 255.0)) {
                tile_counts[slot] = 0u;
                return;
            }
            projected[slot].mean_depth.w = opacity;
            // The footprint shrinks with the opacity; step 3 writes the keys of the new one, and one
            // that holds no pixel centre any more draws nothing.
            if (frame.exact_tiles != 0u) {
                vec2 mean = projected[slot].mean_depth.xy;
                uint tiles = tile_footprint_count(tile_footprint(mean, projected[slot].conic, opacity));
                tile_counts[slot] = tiles;
                if (tiles == 0u) return;
            }
        }
        atomicAdd(stats.visible, 1u);
        atomicAdd(stats.per_level[level - 1u], 1u);
    } else {
        tile_counts[slot] = 0u;
    }
}
