// Picking (SplatRenderer::pick, docs/picking.md), between step 5 and the raster: for each pixel asked
// this frame, one invocation walks the pixel's tile front to back as the raster does (the same sorted
// splats, the same α, the same stop at the mesh surface and before T would fall below 1e-4) and finds
// the splat with which the accumulated opacity first passes ½: its view depth and its instance
// (ProjectedSplat::color.w). Below render scale 1 the pixel is the low-resolution texel its centre
// falls in, stopped at the output pixel's own mesh depth. A frame drawn in strips answers each pixel in
// the strip that holds its row.
#include "common_splat_bindings.glsl"
#include "common_splat_alpha.glsl"

#ifndef RASTER_TILE_SIZE
#define RASTER_TILE_SIZE SPLAT_TILE_SIZE
#endif
layout(local_size_x = SPLAT_MAX_PICKS) in;
layout(std430, binding = SPLAT_BINDING_PROJECTED) readonly buffer Projected { ProjectedSplat projected[]; };
layout(std430, binding = SPLAT_BINDING_VALUES) readonly buffer Values { uint values[]; };
layout(std430, binding = SPLAT_BINDING_TILE_RANGES) readonly buffer Ranges { uvec2 ranges[]; };
layout(std430, binding = SPLAT_BINDING_PICKS) buffer Picks { SplatPicks picks; };
layout(binding = SPLAT_TEXTURE_VIEW_DEPTH) uniform sampler2D view_depth;

void main() {
    uint k = gl_LocalInvocationIndex;
    if (k >= picks.count.x) return;
    uvec2 pixel = picks.pixels[k].xy;
    uint row = pixel.y / RASTER_TILE_SIZE;
    if (row < frame.strip_first_row || row >= frame.strip_end_row) return;
    float mesh_depth = texelFetch(view_depth, ivec2(picks.pixels[k].zw), 0).r;
    uvec2 range = ranges[(pixel.y / RASTER_TILE_SIZE) * frame.tiles.x + pixel.x / RASTER_TILE_SIZE];
    vec2 centre = vec2(pixel) + 0.5;
    float transmittance = 1.0;
    uvec4 answer = uvec4(floatBitsToUint(SPLAT_INFINITY), 0u, 0u, 0u);
    for (uint j = range.x; j < range.y; ++j) {
        ProjectedSplat s = projected[values[j]];
        if (s.mean_depth.z >= mesh_depth) break;
        float alpha = splat_alpha(centre - s.mean_depth.xy, s.conic, s.mean_depth.w);
        if (alpha < 1.0 / 255.0) continue;
        float next = transmittance * (1.0 - alpha);
        if (next < 1e-4) break;
        if (next < 0.5) {
            answer.xy = uvec2(floatBitsToUint(s.mean_depth.z), floatBitsToUint(s.color.w) & ~SPLAT_BUDGET_PACK_FLAG);
            break;
        }
        transmittance = next;
    }
    picks.answers[k] = answer;
}
