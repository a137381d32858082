// Step 5, tile ranges: after the sort, each tile's keys are contiguous; record [begin, end). Keys of
// tile tile_count (step 3's filler, never expected) belong to no tile.
#include "common_splat_bindings.glsl"

layout(local_size_x = SPLAT_RANGES_WORKGROUP_SIZE) in;
layout(std430, binding = SPLAT_BINDING_KEYS) readonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = SPLAT_BINDING_TILE_RANGES) buffer Ranges { uvec2 ranges[]; };
layout(std430, binding = SPLAT_BINDING_ARGS) readonly buffer Args { uvec4 args; };  // w = keys in use

uint key_tile(uvec2 key) {
    return frame.key_depth_bits == 0u ? key.y : key.x >> frame.key_depth_bits;
}

#ifdef SPLAT_INPUT_TEXELS
// Texel fetches instead of storage loads on CPU drivers (as in splat_project).
layout(binding = SPLAT_TEXTURE_SORTED_KEYS) uniform usamplerBuffer key_texels;  // rg32ui
uvec2 load_key(uint i) { return texelFetch(key_texels, int(i)).xy; }
#else
uvec2 load_key(uint i) { return keys[i]; }
#endif

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint count = args.w;
    if (i >= count) return;
    uint tile = key_tile(load_key(i));
    if (tile >= frame.tile_count) return;
    if (i == 0u || key_tile(load_key(i - 1u)) != tile) ranges[tile].x = i;
    if (i + 1u == count || key_tile(load_key(i + 1u)) != tile) ranges[tile].y = i + 1u;
}
