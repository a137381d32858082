// Step 3, bin: one workgroup per cluster step 1b projected, one invocation per splat it wrote. Every
// splat writes one sort key per tile of its footprint (common_splat_tiles.glsl): the cluster's keys
// start where the scan over the clusters put them, and its splats' keys follow in their Gaussians'
// order from the first key step 1b (or 1d) gave each, so every key's position is the same from run to
// run. Pairs beyond the key capacity are dropped and the frame is flagged (splat_dispatch_args), never
// written out of bounds.
//
// Keys (docs/algorithms.md §1, "Sort keys"): with frame.key_depth_bits == 0, uvec2(depth as float
// bits, tile), sorted on all 32 depth bits and the tile's bits. Otherwise one word,
// (tile << D) | depth_q with D = key_depth_bits: depth_q is the depth's float bits less the frame's
// smallest (FrameCounters::depth_range), shifted right just enough to fit D bits. Positive floats
// order like their bits, so depth_q orders like the depth; two depths share a step only when they
// differ by less than 2^(shift − 23) of the depth (2^-13 for D = 16 and depths spanning a factor of
// 256), and then keep their order here, which is their Gaussians' index order (the sort is stable).
#include "common_splat_bindings.glsl"

layout(local_size_x = SPLAT_PROJECT_WORKGROUP_SIZE) in;
layout(std430, binding = SPLAT_BINDING_PROJECTED) readonly buffer Projected { ProjectedSplat projected[]; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_PAIRS) readonly buffer ClusterKeys { uint cluster_keys[]; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_SPLATS) readonly buffer ClusterSplats { uvec2 cluster_splats[]; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_LIST) readonly buffer ClusterList { uvec4 dispatch; uint ids[]; } cluster_list;
#ifdef SPLAT_ONE_WORD_KEYS  // frame.key_depth_bits > 0
layout(std430, binding = SPLAT_BINDING_KEYS) writeonly buffer Keys { uint keys[]; };
#else
layout(std430, binding = SPLAT_BINDING_KEYS) writeonly buffer Keys { uvec2 keys[]; };
#endif
layout(std430, binding = SPLAT_BINDING_VALUES) writeonly buffer Values { uint values[]; };
layout(std430, binding = SPLAT_BINDING_STATS) readonly buffer Stats { FrameCounters stats; };

#include "common_splat_tiles.glsl"

#ifdef SPLAT_INPUT_TEXELS
// Texel fetches instead of storage loads on CPU drivers (as in splat_project).
layout(binding = SPLAT_TEXTURE_PROJECTED_WORDS) uniform usamplerBuffer projected_words;  // rgba32ui, 3 per splat
ProjectedSplat load_projected(uint index) {
    int b = int(index) * 3;
    return ProjectedSplat(uintBitsToFloat(texelFetch(projected_words, b)),
                          uintBitsToFloat(texelFetch(projected_words, b + 1)),
                          uintBitsToFloat(texelFetch(projected_words, b + 2)));
}
uint load_key_word(uint index) { return texelFetch(projected_words, int(index) * 3 + 1).w; }
#else
ProjectedSplat load_projected(uint index) { return projected[index]; }
uint load_key_word(uint index) { return floatBitsToUint(projected[index].conic.w); }
#endif

uint g_begin, g_end, g_next, g_index;
uvec2 g_depth_key;  // x: the depth part of the key, y: its shift into the key (D, or 0 for uvec2 keys)

void emit(uint tile) {
    if (g_next >= g_end || g_next >= frame.key_capacity) return;
#ifdef SPLAT_ONE_WORD_KEYS
    keys[g_next] = (tile << g_depth_key.y) | g_depth_key.x;
#else
    keys[g_next] = uvec2(g_depth_key.x, tile);
#endif
    values[g_next] = g_index;
    ++g_next;
}

uvec2 depth_key(float depth) {
    uint bits = floatBitsToUint(depth);
    uint d = frame.key_depth_bits;
    if (d == 0u) return uvec2(bits, 0u);
    uint lo = ~stats.depth_range.y, range = stats.depth_range.x - lo;
    int shift = max(findMSB(range) + 1 - int(d), 0);
    return uvec2((bits - lo) >> uint(shift), d);
}

// The first key within its cluster of the splat at `index` (steps 1b and 1d, ProjectedSplat::conic.w).
uint first_key(uint index) {
    return load_key_word(index) & ~SPLAT_BUDGET_PACK_FLAG;
}

void main() {
    uint lid = gl_LocalInvocationIndex;
    uint cluster = cluster_list.ids[gl_WorkGroupID.x];
    uvec2 splats = cluster_splats[cluster];
    if (lid >= splats.y) return;
    ProjectedSplat s = load_projected(splats.x + lid);
    // The splat's keys end where the next splat's begin; the cluster's last fills what is left of the
    // cluster's range, which ends where the next cluster's begins.
    uint cluster_first = cluster_keys[cluster], cluster_end = cluster_keys[cluster + 1u];
    g_begin = min(cluster_first + first_key(splats.x + lid), cluster_end);
    g_end = lid + 1u == splats.y ? cluster_end : min(cluster_first + first_key(splats.x + lid + 1u), cluster_end);
    g_next = g_begin;
    g_index = splats.x + lid;
    g_depth_key = depth_key(s.mean_depth.z);
    TileFootprint f = tile_footprint(s.mean_depth.xy, s.conic, s.mean_depth.w);
    for (uint ty = f.rect.y; g_begin < g_end && ty < f.rect.w; ++ty) {
        uvec2 span = frame.exact_tiles != 0u ? tile_row_span(f, ty) : f.rect.xz;
        for (uint tx = span.x; tx < span.y; ++tx) emit(ty * frame.tiles.x + tx);
    }
    // Step 1b counted the same footprint, so nothing is left; should a driver round the two
    // differently, the rest of the range gets keys of tile tile_count, which sort last and belong to
    // no tile (splat_tile_ranges skips them).
    while (g_next < g_end && g_next < frame.key_capacity) emit(frame.tile_count);
}
