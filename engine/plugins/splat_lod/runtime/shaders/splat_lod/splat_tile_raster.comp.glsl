// Step 6, raster + composite: one workgroup per tile (RASTER_TILE_SIZE = 4, 8 or 16 px a side,
// SplatPassSettings::tile_size), one invocation per pixel, walking the tile's splats front to back.
// Per pixel (docs/algorithms.md §1): α = min(0.99, o·exp(−½ dᵀ Σ⁻¹ d)), skip α < 1/255, stop before T
// would fall below 1e−4, stop at the mesh surface; output C + T·mesh_colour (display space).
//
// How the splats reach the pixels (SplatPassSettings::raster_fetch, docs/algorithms.md §1 "Raster"):
// - texel (RASTER_FETCH_SHARED undefined): every invocation inside the image reads each splat itself
//   through buffer textures (the values and the projected splats as texels) and stops on its own; a
//   SIMD group or warp stops when all its pixels have. Mesa's llvmpipe turns a storage-buffer load
//   into a loop over the SIMD lanes with a branch per lane and component, and a texel fetch into one
//   gather: on biker at 1280×720 the raster took 405 ms this way against 3,989 ms with
//   storage-buffer loads (the same bytes).
// - RASTER_FETCH_SHARED: the workgroup stages batches of the tile's splats in shared memory, one
//   splat per invocation, and every pixel walks the batch; between batches the tile stops as soon as
//   every pixel in it is done (saturated, behind the mesh or outside the image). This is the
//   pattern GPU rasterisers use (each splat read once per tile); on llvmpipe shared memory is read
//   lane by lane like storage buffers, so there it is the slower one.
//
// With SPLAT_GRADIENTS defined (render scale below 1, docs/algorithms.md §5) the pixels are low-resolution
// texels and nothing is composited here: the pass writes C and A with their analytic ∂/∂x, ∂/∂y and
// ∂²/∂x∂y (Niedermayr et al. Eqs. 8–14) and a front depth for the upscale pass. A texel is cut at the FARTHEST
// mesh depth among the output pixels it stands for, so no splat is lost where any of them would
// show it; the upscale pass decides per output pixel, with the front depth, where the mesh wins.
//
// Depth (docs/algorithms.md §1, "Depth"): per pixel the depth dₘ of the splat with which the
// accumulated opacity first exceeds ½ and the expected depth Σ dᵢαᵢTᵢ / A. At render scale 1 the pass
// leaves min(mesh depth, dₘ) in the target's view depth for the passes after it (and with
// SPLAT_DEPTH_IMAGE both depths in their own image); below it, both go to the front image.
#include "common_splat_bindings.glsl"
#include "common_splat_alpha.glsl"

#ifndef RASTER_TILE_SIZE
#define RASTER_TILE_SIZE SPLAT_TILE_SIZE
#endif
layout(local_size_x = RASTER_TILE_SIZE, local_size_y = RASTER_TILE_SIZE) in;
#if defined(RASTER_FETCH_SHARED)
layout(std430, binding = SPLAT_BINDING_PROJECTED) readonly buffer Projected { ProjectedSplat projected[]; };
layout(std430, binding = SPLAT_BINDING_VALUES) readonly buffer Values { uint values[]; };
#else
layout(binding = SPLAT_TEXTURE_PROJECTED) uniform samplerBuffer projected_texels;  // 3 RGBA32F per splat
layout(binding = SPLAT_TEXTURE_VALUES) uniform usamplerBuffer value_texels;         // R32UI per key
#endif
layout(std430, binding = SPLAT_BINDING_TILE_RANGES) readonly buffer Ranges { uvec2 ranges[]; };
layout(binding = SPLAT_TEXTURE_VIEW_DEPTH) uniform sampler2D view_depth;
#ifdef SPLAT_GRADIENTS
layout(binding = SPLAT_IMAGE_LOW_VALUE, rgba32f) uniform writeonly image2D low_value;
layout(binding = SPLAT_IMAGE_LOW_DX, rgba32f) uniform writeonly image2D low_dx;
layout(binding = SPLAT_IMAGE_LOW_DY, rgba32f) uniform writeonly image2D low_dy;
layout(binding = SPLAT_IMAGE_LOW_DXY, rgba32f) uniform writeonly image2D low_dxy;
layout(binding = SPLAT_IMAGE_LOW_FRONT, rgba32f) uniform writeonly image2D low_front;

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
layout(binding = SPLAT_IMAGE_VIEW_DEPTH, r32f) uniform coherent image2D view_depth_image;
#ifdef SPLAT_DEPTH_IMAGE
layout(binding = SPLAT_IMAGE_SPLAT_DEPTH, rg32f) uniform writeonly image2D splat_depth;
#endif
#endif

// What the blend of one splat needs (ProjectedSplat without its tile rectangle).
struct RasterSplat {
    vec4 mean_depth;  // x, y, view depth, opacity
    vec4 conic;       // xx, xy, yy
    vec3 color;
};

// The pixel's state, walked front to back by blend().
vec2 g_centre;
float g_mesh_depth;
vec3 g_color = vec3(0.0);
float g_transmittance = 1.0;
float g_depth_sum = 0.0;  // Σ dᵢαᵢTᵢ
float g_median;           // the depth at which T first falls below ½ (+inf before)
#ifdef SPLAT_GRADIENTS
// ∂x, ∂y, ∂²xy of (C, A) (docs/algorithms.md §5); .w holds the accumulated alpha's derivatives.
vec4 g_grad_x = vec4(0.0), g_grad_y = vec4(0.0), g_grad_xy = vec4(0.0);
#endif

// Blends one splat into the pixel; false once the pixel is done (behind the mesh or saturated).
bool blend(RasterSplat s) {
    vec4 md = s.mean_depth;
    if (md.z >= g_mesh_depth) return false;  // sorted by depth: everything after is behind the mesh too
    vec2 d = g_centre - md.xy;
    vec4 q = s.conic;
    float alpha = splat_alpha(d, q, md.w);
    if (alpha < 1.0 / 255.0) return true;
    float next = g_transmittance * (1.0 - alpha);
    if (next < 1e-4) return false;  // stop before T would fall below 1e-4
#ifdef SPLAT_GRADIENTS
    // g = −½ dᵀ C d: g_x = −(Cxx dx + Cxy dy), g_y = −(Cxy dx + Cyy dy), g_xy = −Cxy; the 0.99
    // clamp and the 1/255 cut are not differentiated. With T = 1 − A, colour and alpha change
    // by the same scalar times (c, 1): C_x += c (α_x T − α A_x) and A_x ← A_x (1 − α) + T α_x
    // = A_x + (α_x T − α A_x); likewise for y, and for xy with α_xy T − α_x A_y − α_y A_x − α A_xy.
    float g_x = -(q.x * d.x + q.y * d.y), g_y = -(q.y * d.x + q.z * d.y);
    float alpha_x = alpha * g_x, alpha_y = alpha * g_y, alpha_xy = alpha * (g_x * g_y - q.y);
    vec4 weight = vec4(s.color, 1.0);
    float t = g_transmittance;
    float k_xy = alpha_xy * t - alpha_x * g_grad_y.w - alpha_y * g_grad_x.w - alpha * g_grad_xy.w;
    g_grad_x += weight * (alpha_x * t - alpha * g_grad_x.w);
    g_grad_y += weight * (alpha_y * t - alpha * g_grad_y.w);
    g_grad_xy += weight * k_xy;
#endif
    g_color += s.color * (alpha * g_transmittance);
    g_depth_sum += md.z * (alpha * g_transmittance);
    if (g_transmittance >= 0.5 && next < 0.5) g_median = md.z;
    g_transmittance = next;
    return true;
}

#if defined(RASTER_FETCH_SHARED)
#define RASTER_BATCH (RASTER_TILE_SIZE * RASTER_TILE_SIZE)
shared vec4 s_mean_depth[RASTER_BATCH];
shared vec4 s_conic[RASTER_BATCH];
shared vec3 s_color[RASTER_BATCH];
shared uint s_done;  // pixels of the tile that are done

void walk(uvec2 range, bool inside) {
    uint lid = gl_LocalInvocationIndex;
    bool live = inside;
    if (lid == 0u) s_done = 0u;
    barrier();
    if (!live) atomicAdd(s_done, 1u);
    for (uint batch = range.x; batch < range.y; batch += RASTER_BATCH) {
        barrier();  // the last batch is walked and s_done is final: the same value for every invocation
        if (s_done == RASTER_BATCH) break;
        if (batch + lid < range.y) {
            ProjectedSplat p = projected[values[batch + lid]];
            s_mean_depth[lid] = p.mean_depth;
            s_conic[lid] = p.conic;
            s_color[lid] = p.color.rgb;
        }
        barrier();
        uint n = min(RASTER_BATCH, range.y - batch);
        for (uint j = 0u; live && j < n; ++j) live = blend(RasterSplat(s_mean_depth[j], s_conic[j], s_color[j]));
        if (!live && inside) atomicAdd(s_done, 1u);
        inside = live;  // counted once
    }
}
#else
RasterSplat fetch(uint k) {
    int base = int(texelFetch(value_texels, int(k)).x) * 3;
    return RasterSplat(texelFetch(projected_texels, base), texelFetch(projected_texels, base + 1),
                       texelFetch(projected_texels, base + 2).rgb);
}

void walk(uvec2 range) {
    for (uint k = range.x; k < range.y; ++k)
        if (!blend(fetch(k))) break;
}
#endif

void main() {
    // In strips (SplatPassSettings::frame_memory_limit) the dispatch covers the strip's tile rows only.
    uvec2 tile_xy = gl_WorkGroupID.xy + uvec2(0u, frame.strip_first_row);
    ivec2 pixel = ivec2(tile_xy * uint(RASTER_TILE_SIZE) + gl_LocalInvocationID.xy);
    ivec2 size = ivec2(frame.raster_size);
    bool inside = all(lessThan(pixel, size));
    uint tile = tile_xy.y * frame.tiles.x + tile_xy.x;
    g_centre = vec2(pixel) + 0.5;
    g_median = SPLAT_INFINITY;
#ifdef SPLAT_GRADIENTS
    g_mesh_depth = inside ? footprint_mesh_depth(pixel) : 0.0;
#else
    g_mesh_depth = inside ? imageLoad(view_depth_image, pixel).r : 0.0;
#endif
#if defined(RASTER_FETCH_SHARED)
    walk(ranges[tile], inside);  // every invocation stages splats, inside the image or not
#else
    if (inside) walk(ranges[tile]);  // outside the image: no loads
#endif
    if (!inside) return;
    float accumulated = 1.0 - g_transmittance;
    float expected = accumulated > 0.0 ? g_depth_sum / accumulated : SPLAT_INFINITY;
#ifdef SPLAT_GRADIENTS
    imageStore(low_value, pixel, vec4(g_color, accumulated));
    imageStore(low_dx, pixel, g_grad_x);
    imageStore(low_dy, pixel, g_grad_y);
    imageStore(low_dxy, pixel, g_grad_xy);
    float front = g_median < SPLAT_INFINITY ? g_median : g_mesh_depth;
    imageStore(low_front, pixel, vec4(front, g_median, expected, 0.0));
#else
    vec3 behind = imageLoad(color_image, pixel).rgb;  // mesh colour or background
    imageStore(color_image, pixel, vec4(g_color + g_transmittance * behind, 1.0));
    imageStore(view_depth_image, pixel, vec4(min(g_mesh_depth, g_median)));
#ifdef SPLAT_DEPTH_IMAGE
    imageStore(splat_depth, pixel, vec4(g_median, expected, 0.0, 0.0));
#endif
#endif
}
