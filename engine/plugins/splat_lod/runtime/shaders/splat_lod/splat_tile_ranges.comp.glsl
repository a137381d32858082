// Step 5, tile ranges: after the sort, each tile's keys are contiguous; record [begin, end). Keys of
// tile tile_count (step 3's filler, never expected) belong to no tile.
#include "common_splat_bindings.glsl"

layout(local_size_x = SPLAT_RANGES_WORKGROUP_SIZE) in;
#ifdef SPLAT_ONE_WORD_KEYS  // frame.key_depth_bits > 0: (tile << D) | depth_q
layout(std430, binding = SPLAT_BINDING_KEYS) readonly buffer Keys { uint keys[]; };
uint key_tile(uint key) { return key >> frame.key_depth_bits; }
#else  // (depth bits, tile)
layout(std430, binding = SPLAT_BINDING_KEYS) readonly buffer Keys { uvec2 keys[]; };
uint key_tile(uvec2 key) { return key.y; }
#endif
layout(std430, binding = SPLAT_BINDING_TILE_RANGES) buffer Ranges { uvec2 ranges[]; };
layout(std430, binding = SPLAT_BINDING_ARGS) readonly buffer Args { uvec4 args; };  // w = keys in use


#ifdef SPLAT_INPUT_TEXELS
// Texel fetches instead of storage loads on CPU drivers (as in splat_project).
layout(binding = SPLAT_TEXTURE_SORTED_KEYS) uniform usamplerBuffer key_texels;  // r32ui or rg32ui
#ifdef SPLAT_ONE_WORD_KEYS
uint load_key(uint i) { return texelFetch(key_texels, int(i)).x; }
#else
uvec2 load_key(uint i) { return texelFetch(key_texels, int(i)).xy; }
#endif
#else
#ifdef SPLAT_ONE_WORD_KEYS
uint load_key(uint i) { return keys[i]; }
#else
uvec2 load_key(uint i) { return keys[i]; }
#endif
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
