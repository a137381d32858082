// Step 5, tile ranges: after the sort, each tile's keys are contiguous; record [begin, end).
#include "common_splat_bindings.glsl"

layout(local_size_x = SPLAT_RANGES_WORKGROUP_SIZE) in;
layout(std430, binding = SPLAT_BINDING_KEYS) readonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = SPLAT_BINDING_TILE_RANGES) buffer Ranges { uvec2 ranges[]; };
layout(std430, binding = SPLAT_BINDING_ARGS) readonly buffer Args { uvec4 args; };  // w = keys in use

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint count = args.w;
    if (i >= count) return;
    uint tile = keys[i].y;
    if (i == 0u || keys[i - 1u].y != tile) ranges[tile].x = i;
    if (i + 1u == count || keys[i + 1u].y != tile) ranges[tile].y = i + 1u;
}
