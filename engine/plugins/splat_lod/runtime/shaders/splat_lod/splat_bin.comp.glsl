// Step 3, bin: every visible splat writes one (depth, tile) key per tile its extent touches,
// into the key range the scan of tile counts gave it. Pairs beyond the key capacity are
// dropped and the frame is flagged (splat_dispatch_args), never written out of bounds.
#include "common_splat_bindings.glsl"

layout(local_size_x = SPLAT_BIN_WORKGROUP_SIZE) in;
layout(std430, binding = SPLAT_BINDING_PROJECTED) readonly buffer Projected { ProjectedSplat projected[]; };
layout(std430, binding = SPLAT_BINDING_TILE_COUNTS) readonly buffer KeyOffsets { uint key_offsets[]; };
layout(std430, binding = SPLAT_BINDING_KEYS) writeonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = SPLAT_BINDING_VALUES) writeonly buffer Values { uint values[]; };

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= frame.gaussian_count) return;
    uint begin = key_offsets[index];
    uint end = key_offsets[index + 1u];
    if (begin == end) return;
    ProjectedSplat s = projected[index];
    uint depth_bits = floatBitsToUint(s.mean_depth.z);  // positive floats order like their bits
    uint capacity = frame.key_capacity;
    uint k = begin;
    for (uint ty = s.tile_rect.y; ty < s.tile_rect.w; ++ty) {
        for (uint tx = s.tile_rect.x; tx < s.tile_rect.z; ++tx) {
            if (k >= capacity) return;
            keys[k] = uvec2(depth_bits, ty * frame.tiles.x + tx);
            values[k] = index;
            ++k;
        }
    }
}
