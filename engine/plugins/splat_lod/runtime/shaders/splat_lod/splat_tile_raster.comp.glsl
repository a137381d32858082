// Step 6, raster + composite: one workgroup per tile (RASTER_TILE_SIZE = 4, 8 or 16 px a side,
// SplatPassSettings::tile_size), one invocation per pixel, reading the tile's splats (sorted front to
// back) straight from the buffers. Staging batches in shared
// memory with barriers was measured 1.8× slower on llvmpipe (biker, 1280×720: 1360 ms against
// 740 ms). Per pixel (docs/algorithms.md §1): α = min(0.99, o·exp(−½ dᵀ Σ⁻¹ d)), skip α < 1/255,
// stop before T would fall below 1e−4, stop at the mesh surface; output C + T·mesh_colour (display
// space).
//
// With SPLAT_GRADIENTS defined (render scale below 1, docs/algorithms.md §5) the pixels are low-resolution
// texels and nothing is composited here: the pass writes C and A with their analytic ∂/∂x, ∂/∂y and
// ∂²/∂x∂y (paper Eqs. 8–14) and a front depth for the upscale pass. A texel is cut at the FARTHEST
// mesh depth among the output pixels it stands for, so no splat is lost where any of them would
// show it; the upscale pass decides per output pixel, with the front depth, where the mesh wins.
#include "common_splat_bindings.glsl"

#ifndef RASTER_TILE_SIZE
#define RASTER_TILE_SIZE SPLAT_TILE_SIZE
#endif
layout(local_size_x = RASTER_TILE_SIZE, local_size_y = RASTER_TILE_SIZE) in;
layout(std430, binding = SPLAT_BINDING_PROJECTED) readonly buffer Projected { ProjectedSplat projected[]; };
layout(std430, binding = SPLAT_BINDING_VALUES) readonly buffer Values { uint values[]; };
layout(std430, binding = SPLAT_BINDING_TILE_RANGES) readonly buffer Ranges { uvec2 ranges[]; };
layout(binding = SPLAT_TEXTURE_VIEW_DEPTH) uniform sampler2D view_depth;
#ifdef SPLAT_GRADIENTS
layout(binding = SPLAT_IMAGE_LOW_VALUE, rgba32f) uniform writeonly image2D low_value;
layout(binding = SPLAT_IMAGE_LOW_DX, rgba32f) uniform writeonly image2D low_dx;
layout(binding = SPLAT_IMAGE_LOW_DY, rgba32f) uniform writeonly image2D low_dy;
layout(binding = SPLAT_IMAGE_LOW_DXY, rgba32f) uniform writeonly image2D low_dxy;
layout(binding = SPLAT_IMAGE_LOW_FRONT, r32f) uniform writeonly image2D low_front;

// The farthest mesh depth over the output pixels whose sample point rounds to this texel: those
// with (x + 0.5)·s − 0.5 in [i − 0.5, i + 0.5), i.e. x in [i/s − 0.5, (i + 1)/s − 0.5).
float footprint_mesh_depth(ivec2 texel) {
    ivec2 output_size = ivec2(frame.output_size);
    float f = frame.inverse_render_scale;
    ivec2 lo = ivec2(ceil(vec2(texel) * f - 0.5));
    ivec2 hi = min(ivec2(ceil(vec2(texel + 1) * f - 0.5)), output_size);  // exclusive
    lo = min(lo, output_size - 1);
    hi = max(hi, lo + 1);
    float depth = 0.0;
    for (int y = lo.y; y < hi.y; ++y)
        for (int x = lo.x; x < hi.x; ++x) depth = max(depth, texelFetch(view_depth, ivec2(x, y), 0).r);
    return depth;
}
#else
layout(binding = SPLAT_IMAGE_COLOR, rgba8) uniform coherent image2D color_image;
#endif

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.raster_size);
    bool inside = all(lessThan(pixel, size));
    uint tile = gl_WorkGroupID.y * frame.tiles.x + gl_WorkGroupID.x;
    uvec2 range = ranges[tile];
    vec2 centre = vec2(pixel) + 0.5;
#ifdef SPLAT_GRADIENTS
    float mesh_depth = inside ? footprint_mesh_depth(pixel) : 0.0;
    // ∂x, ∂y, ∂²xy of (C, A) (docs/algorithms.md §5); .w holds the accumulated alpha's derivatives.
    vec4 grad_x = vec4(0.0), grad_y = vec4(0.0), grad_xy = vec4(0.0);
    float front = mesh_depth;
#else
    float mesh_depth = inside ? texelFetch(view_depth, pixel, 0).r : 0.0;
#endif

    vec3 color = vec3(0.0);
    float transmittance = 1.0;
    for (uint k = range.x; inside && k < range.y; ++k) {
        ProjectedSplat s = projected[values[k]];
        vec4 md = s.mean_depth;
        if (md.z >= mesh_depth) break;  // sorted by depth: everything after is behind the mesh too
        vec2 d = centre - md.xy;
        vec4 q = s.conic;
        float power = -0.5 * (q.x * d.x * d.x + 2.0 * q.y * d.x * d.y + q.z * d.y * d.y);
        float alpha = min(0.99, md.w * exp(power));
        if (alpha < 1.0 / 255.0) continue;
        float next = transmittance * (1.0 - alpha);
        if (next < 1e-4) break;  // stop before T would fall below 1e-4
#ifdef SPLAT_GRADIENTS
        // g = −½ dᵀ C d: g_x = −(Cxx dx + Cxy dy), g_y = −(Cxy dx + Cyy dy), g_xy = −Cxy; the 0.99
        // clamp and the 1/255 cut are not differentiated. With T = 1 − A, colour and alpha change
        // by the same scalar times (c, 1): C_x += c (α_x T − α A_x) and A_x ← A_x (1 − α) + T α_x
        // = A_x + (α_x T − α A_x); likewise for y, and for xy with α_xy T − α_x A_y − α_y A_x − α A_xy.
        float g_x = -(q.x * d.x + q.y * d.y), g_y = -(q.y * d.x + q.z * d.y);
        float alpha_x = alpha * g_x, alpha_y = alpha * g_y, alpha_xy = alpha * (g_x * g_y - q.y);
        vec4 weight = vec4(s.color.rgb, 1.0);
        float k_xy = alpha_xy * transmittance - alpha_x * grad_y.w - alpha_y * grad_x.w - alpha * grad_xy.w;
        grad_x += weight * (alpha_x * transmittance - alpha * grad_x.w);
        grad_y += weight * (alpha_y * transmittance - alpha * grad_y.w);
        grad_xy += weight * k_xy;
        if (transmittance >= 0.5 && next < 0.5) front = md.z;
#endif
        color += s.color.rgb * (alpha * transmittance);
        transmittance = next;
    }
    if (!inside) return;
#ifdef SPLAT_GRADIENTS
    imageStore(low_value, pixel, vec4(color, 1.0 - transmittance));
    imageStore(low_dx, pixel, grad_x);
    imageStore(low_dy, pixel, grad_y);
    imageStore(low_dxy, pixel, grad_xy);
    imageStore(low_front, pixel, vec4(front));
#else
    vec3 behind = imageLoad(color_image, pixel).rgb;  // mesh colour or background
    imageStore(color_image, pixel, vec4(color + transmittance * behind, 1.0));
#endif
}
