// Step 3, bin: every visible splat writes one sort key per tile of its footprint
// (common_splat_tiles.glsl), into the key range the scan of tile counts gave it. Pairs beyond the key
// capacity are dropped and the frame is flagged (splat_dispatch_args), never written out of bounds.
//
// Keys (docs/algorithms.md §1, "Sort keys"): with frame.key_depth_bits == 0, uvec2(depth as float
// bits, tile), sorted on all 32 depth bits and the tile's bits. Otherwise one word,
// (tile << D) | depth_q with D = key_depth_bits: depth_q is the depth's float bits less the frame's
// smallest (FrameCounters::depth_range), shifted right just enough to fit D bits. Positive floats
// order like their bits, so depth_q orders like the depth; two depths share a step only when they
// differ by less than 2^(shift − 23) of the depth (2^-13 for D = 16 and depths spanning a factor of
// 256), and then keep their slots' order, which is their Gaussians' index order (the sort is stable).
#include "common_splat_bindings.glsl"

layout(local_size_x = SPLAT_BIN_WORKGROUP_SIZE) in;
layout(std430, binding = SPLAT_BINDING_PROJECTED) readonly buffer Projected { ProjectedSplat projected[]; };
layout(std430, binding = SPLAT_BINDING_TILE_COUNTS) readonly buffer KeyOffsets { uint key_offsets[]; };
layout(std430, binding = SPLAT_BINDING_KEYS) writeonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = SPLAT_BINDING_VALUES) writeonly buffer Values { uint values[]; };
layout(std430, binding = SPLAT_BINDING_STATS) readonly buffer Stats { FrameCounters stats; };

#include "common_splat_tiles.glsl"

#ifdef SPLAT_INPUT_TEXELS
// Texel fetches instead of storage loads on CPU drivers (as in splat_project).
layout(binding = SPLAT_TEXTURE_PROJECTED_WORDS) uniform usamplerBuffer projected_words;  // rgba32ui, 4 per splat
layout(binding = SPLAT_TEXTURE_KEY_OFFSETS) uniform usamplerBuffer key_offset_texels;    // r32ui
uint key_offset(uint index) { return texelFetch(key_offset_texels, int(index)).x; }
ProjectedSplat load_projected(uint index) {
    int b = int(index) * 4;
    return ProjectedSplat(uintBitsToFloat(texelFetch(projected_words, b)),
                          uintBitsToFloat(texelFetch(projected_words, b + 1)),
                          uintBitsToFloat(texelFetch(projected_words, b + 2)), texelFetch(projected_words, b + 3));
}
#else
uint key_offset(uint index) { return key_offsets[index]; }
ProjectedSplat load_projected(uint index) { return projected[index]; }
#endif

uint g_begin, g_end, g_next, g_index;
uvec2 g_depth_key;  // x: the depth part of the key, y: its shift into the key (D, or 0 for uvec2 keys)

void emit(uint tile) {
    if (g_next >= g_end || g_next >= frame.key_capacity) return;
    bool wide = frame.key_depth_bits == 0u;
    keys[g_next] = wide ? uvec2(g_depth_key.x, tile) : uvec2((tile << g_depth_key.y) | g_depth_key.x, 0u);
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

void main() {
    uint index = gl_GlobalInvocationID.x;  // the splat's slot
    if (index >= frame.slot_count) return;
    g_begin = key_offset(index);
    g_end = key_offset(index + 1u);
    if (g_begin == g_end) return;
    ProjectedSplat s = load_projected(index);
    g_next = g_begin;
    g_index = index;
    g_depth_key = depth_key(s.mean_depth.z);
    if (frame.exact_tiles != 0u) {
        TileFootprint f = tile_footprint(s.mean_depth.xy, s.conic, s.mean_depth.w);
        for (uint ty = f.rect.y; ty < f.rect.w; ++ty) {
            uvec2 span = tile_row_span(f, ty);
            for (uint tx = span.x; tx < span.y; ++tx) emit(ty * frame.tiles.x + tx);
        }
    } else {
        for (uint ty = s.tile_rect.y; ty < s.tile_rect.w; ++ty)
            for (uint tx = s.tile_rect.x; tx < s.tile_rect.z; ++tx) emit(ty * frame.tiles.x + tx);
    }
    // Step 1b counted the same footprint, so nothing is left; should a driver round the two
    // differently, the rest of the range gets keys of tile tile_count, which sort last and belong to
    // no tile (splat_tile_ranges skips them).
    while (g_next < g_end && g_next < frame.key_capacity) emit(frame.tile_count);
}
