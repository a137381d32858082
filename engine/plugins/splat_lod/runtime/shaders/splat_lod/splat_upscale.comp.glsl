// Step 7 below render scale 1, upscale + composite (docs/algorithms.md §5): one invocation per output
// pixel. Output pixel (x, y) samples the low-resolution splat image at u = (x + 0.5)·s − 0.5,
// v = (y + 0.5)·s − 0.5 (texel centres at integers), clamped to the outermost texel centres, with
// the method chosen by UPSCALE_METHOD (SPLAT_UPSCALER_*: spline, bicubic, bilinear, lanczos3, the order of
// plugin_msgs::Upscaler). The result, clamped to [0, 1], is composited over the full-resolution
// mesh pass: C + (1 − A)·mesh_colour.
//
// Silhouettes: the raster cut each texel at the farthest mesh depth among its output pixels, so the
// low-resolution image holds every splat that any of them could show. Where this pixel's own mesh
// is nearer than the splats' front depth (where their transmittance fell below ½) at all four
// surrounding texels, the mesh hides them and the pixel keeps the mesh colour; mesh edges are
// therefore as sharp as the mesh pass drew them.
//
// Depth is not interpolated like colour: between a near and a far surface an interpolated depth lies
// where there is nothing. Where the upscaled opacity reaches ½ the pixel takes the median depth of the
// nearest of the four texels around it that has one in front of its mesh (the expected depth likewise
// where the opacity is above 0), and leaves min(its mesh depth, that median) in the view depth for the
// passes after it (docs/algorithms.md §1, "Depth").
// The CPU twin is splat_lod/core/upscale.h (upscale_image); the tests compare the two.
#include "common_splat_bindings.glsl"

#ifndef UPSCALE_METHOD
#define UPSCALE_METHOD SPLAT_UPSCALER_SPLINE
#endif

layout(local_size_x = SPLAT_UPSCALE_WORKGROUP_SIZE, local_size_y = SPLAT_UPSCALE_WORKGROUP_SIZE) in;
layout(binding = SPLAT_IMAGE_COLOR, rgba8) uniform coherent image2D color_image;
layout(binding = SPLAT_IMAGE_LOW_VALUE, rgba32f) uniform readonly image2D low_value;
layout(binding = SPLAT_IMAGE_LOW_DX, rgba32f) uniform readonly image2D low_dx;
layout(binding = SPLAT_IMAGE_LOW_DY, rgba32f) uniform readonly image2D low_dy;
layout(binding = SPLAT_IMAGE_LOW_DXY, rgba32f) uniform readonly image2D low_dxy;
layout(binding = SPLAT_IMAGE_LOW_FRONT, rgba32f) uniform readonly image2D low_front;
layout(binding = SPLAT_IMAGE_VIEW_DEPTH, r32f) uniform coherent image2D view_depth_image;
#ifdef SPLAT_DEPTH_IMAGE
layout(binding = SPLAT_IMAGE_SPLAT_DEPTH, rg32f) uniform writeonly image2D splat_depth;
#endif

// The low-resolution image's size (the raster's image size).
#define low_size ivec2(frame.raster_size)

vec4 value_at(ivec2 texel) { return imageLoad(low_value, clamp(texel, ivec2(0), low_size - 1)); }

// Cubic Hermite basis at t: weights of (f0, f1, f'0, f'1), i.e. [1 t t² t³]·M.
vec4 hermite(float t) {
    float t2 = t * t, t3 = t2 * t;
    return vec4(1.0 - 3.0 * t2 + 2.0 * t3, 3.0 * t2 - 2.0 * t3, t - 2.0 * t2 + t3, t3 - t2);
}

// The patch between texels i and i + 1 (per axis) from the corners' values and derivatives;
// corner order (0,0), (1,0), (0,1), (1,1) with the first index along x.
vec4 hermite_patch(vec2 t, vec4 f[4], vec4 fx[4], vec4 fy[4], vec4 fxy[4]) {
    vec4 wx = hermite(t.x), wy = hermite(t.y);
    vec4 result = vec4(0.0);
    for (int c = 0; c < 4; ++c) {
        int cx = c & 1, cy = c >> 1;
        float vx = wx[cx], dx = wx[2 + cx], vy = wy[cy], dy = wy[2 + cy];
        result += vx * vy * f[c] + dx * vy * fx[c] + vx * dy * fy[c] + dx * dy * fxy[c];
    }
    return result;
}

float lanczos3(float x) {
    x = abs(x);
    if (x < 1e-6) return 1.0;
    if (x >= 3.0) return 0.0;
    const float pi = 3.14159265358979;
    return 3.0 * sin(pi * x) * sin(pi * x / 3.0) / (pi * pi * x * x);
}

vec4 sample_low(vec2 uv, ivec2 i, vec2 t) {
    const ivec2 corner[4] = ivec2[](ivec2(0, 0), ivec2(1, 0), ivec2(0, 1), ivec2(1, 1));
#if UPSCALE_METHOD == SPLAT_UPSCALER_SPLINE
    vec4 f[4], fx[4], fy[4], fxy[4];
    for (int c = 0; c < 4; ++c) {
        ivec2 texel = min(i + corner[c], low_size - 1);
        f[c] = imageLoad(low_value, texel);
        fx[c] = imageLoad(low_dx, texel);
        fy[c] = imageLoad(low_dy, texel);
        fxy[c] = imageLoad(low_dxy, texel);
    }
    return hermite_patch(t, f, fx, fy, fxy);
#elif UPSCALE_METHOD == SPLAT_UPSCALER_BICUBIC
    // Finite-difference derivatives (central, neighbours clamped) with a true mixed derivative:
    // in the interior this is Keys' cubic convolution with a = −0.5.
    vec4 n[16];  // texels i − 1 .. i + 2 along x (fastest), j − 1 .. j + 2 along y
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) n[y * 4 + x] = value_at(i + ivec2(x - 1, y - 1));
    vec4 f[4], fx[4], fy[4], fxy[4];
    for (int c = 0; c < 4; ++c) {
        int x = 1 + corner[c].x, y = 1 + corner[c].y;
        f[c] = n[y * 4 + x];
        fx[c] = 0.5 * (n[y * 4 + x + 1] - n[y * 4 + x - 1]);
        fy[c] = 0.5 * (n[(y + 1) * 4 + x] - n[(y - 1) * 4 + x]);
        fxy[c] = 0.25 * (n[(y + 1) * 4 + x + 1] - n[(y - 1) * 4 + x + 1] - n[(y + 1) * 4 + x - 1] + n[(y - 1) * 4 + x - 1]);
    }
    return hermite_patch(t, f, fx, fy, fxy);
#elif UPSCALE_METHOD == SPLAT_UPSCALER_BILINEAR
    vec4 top = mix(value_at(i), value_at(i + ivec2(1, 0)), t.x);
    vec4 bottom = mix(value_at(i + ivec2(0, 1)), value_at(i + ivec2(1, 1)), t.x);
    return mix(top, bottom, t.y);
#else
    // Six taps per axis around uv, weights normalised to 1 per axis.
    float wx[6], wy[6], sx = 0.0, sy = 0.0;
    for (int k = 0; k < 6; ++k) {
        wx[k] = lanczos3(uv.x - float(i.x - 2 + k));
        wy[k] = lanczos3(uv.y - float(i.y - 2 + k));
        sx += wx[k];
        sy += wy[k];
    }
    vec4 result = vec4(0.0);
    for (int y = 0; y < 6; ++y) {
        vec4 row = vec4(0.0);
        for (int x = 0; x < 6; ++x) row += wx[x] * value_at(i + ivec2(x - 2, y - 2));
        result += wy[y] * row;
    }
    return result / (sx * sy);
#endif
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.output_size)))) return;
    float s = frame.render_scale;
    vec2 uv = clamp((vec2(pixel) + 0.5) * s - 0.5, vec2(0.0), vec2(low_size - 1));
    // Patch origin: at most the second-to-last texel, so that t reaches 1 at the last centre.
    ivec2 i = max(min(ivec2(floor(uv)), low_size - 2), ivec2(0));
    vec2 t = uv - vec2(i);

    float mesh = imageLoad(view_depth_image, pixel).r;
    vec4 depths[4];  // the four texels around uv: x front, y median, z expected depth
    float front = SPLAT_INFINITY;
    for (int k = 0; k < 4; ++k) {
        depths[k] = imageLoad(low_front, min(i + ivec2(k & 1, k >> 1), low_size - 1));
        front = min(front, depths[k].x);
    }
    vec2 median_expected = vec2(SPLAT_INFINITY);
    if (mesh >= front) {  // else the mesh hides the splats here
        vec4 splat = clamp(sample_low(uv, i, t), 0.0, 1.0);
        vec3 behind = imageLoad(color_image, pixel).rgb;
        imageStore(color_image, pixel, vec4(splat.rgb + (1.0 - splat.a) * behind, 1.0));
        // Depth: each from the nearest of the four texels that has one in front of this pixel's mesh,
        // the median only where the upscaled opacity reaches ½.
        float nearest_median = 4.0, nearest_expected = 4.0;
        for (int k = 0; k < 4; ++k) {
            vec2 offset = uv - vec2(i + ivec2(k & 1, k >> 1));
            float d = dot(offset, offset);
            if (splat.a >= 0.5 && depths[k].y < mesh && d < nearest_median) {
                nearest_median = d;
                median_expected.x = depths[k].y;
            }
            if (splat.a > 0.0 && depths[k].z < mesh && d < nearest_expected) {
                nearest_expected = d;
                median_expected.y = depths[k].z;
            }
        }
    }
    imageStore(view_depth_image, pixel, vec4(min(mesh, median_expected.x)));
#ifdef SPLAT_DEPTH_IMAGE
    imageStore(splat_depth, pixel, vec4(median_expected, 0.0, 0.0));
#endif
}
