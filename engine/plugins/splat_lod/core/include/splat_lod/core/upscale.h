#pragma once
// Gradient-aware upscaling (docs/algorithms.md §5): the geometry shared by the GPU pass and the CPU
// reference, and the CPU reference upscalers (GL-free, in splat_lod_core) that the GPU's
// upscale pass is tested against.
//
// Rendering at render scale s (0 < s ≤ 1) for an output of W×H pixels: the splats are rasterised
// into a ceil(W·s)×ceil(H·s) image whose pixel coordinates are the output's times s (focal lengths
// and principal point × s, so the low-resolution image may extend up to one texel beyond the
// output's right and bottom edges). Output pixel (x, y) samples the low-resolution image at
// u = (x + 0.5)·s − 0.5, v = (y + 0.5)·s − 0.5 (texel centres at integers), clamped to
// [0, w − 1] × [0, h − 1]: beyond the outermost texel centres the image is extended as a constant.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "splat_lod/msgs/lod_settings.h"

namespace splat_lod::upscale {

// The low-resolution side for an output side and a render scale: ceil(side·s), at least 1. The
// 1e-4 keeps 1920·(1/3) from becoming 641 through float rounding.
inline int low_res_size(int output_side, double render_scale) {
    return std::max(1, static_cast<int>(std::ceil(static_cast<double>(output_side) * render_scale - 1e-4)));
}

// A low-resolution splat image with its analytic derivatives: four channels per texel (r, g, b
// premultiplied colour C and alpha A), row-major with the top row first, derivatives in units of
// low-resolution pixels (x right, y down). `dx`, `dy`, `dxy` are empty when not computed.
struct GradientImage {
    int width = 0;
    int height = 0;
    std::vector<float> value;  // 4 per texel
    std::vector<float> dx;     // ∂/∂x, 4 per texel
    std::vector<float> dy;     // ∂/∂y
    std::vector<float> dxy;    // ∂²/∂x∂y

    std::size_t texel(int x, int y) const {
        return 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x));
    }
};

// A W×H×4 float image, row-major, top row first.
struct Rgba32f {
    int width = 0;
    int height = 0;
    std::vector<float> rgba;
};

// Upscales to out_width × out_height with render scale s (the low-resolution image must be
// low_res_size(out, s) on each side). A sample at u lies in the cell i = min(floor(u), w − 2)
// (0 when w = 1), t = u − i, with corners i and min(i + 1, w − 1); likewise in v. Methods:
// - spline: the Hermite patch of docs/algorithms.md §5 on the analytic derivatives (`dx`, `dy`, `dxy`);
// - bicubic: the same patch on central differences and a true mixed difference, indices clamped:
//   Keys' cubic convolution with a = −0.5 in x and y;
// - bilinear; lanczos3: 6×6 taps of sinc(x)·sinc(x/3), |x| < 3, weights normalised per axis.
// Results are clamped to [0, 1] (a NaN, which only non-finite input can produce, becomes 0); that
// clamp is the only limit on the cubic methods' overshoot. Throws engine::Error on mismatched
// sizes, s outside (0, 1] or NaN, or a spline request without derivatives.
Rgba32f upscale_image(const GradientImage& low, int out_width, int out_height, double render_scale,
                      plugin_msgs::Upscaler method);

// One channel of one output sample before the final clamp, for tests of the interpolants:
// `channel` 0–3 at continuous low-resolution coordinates (u, v) (already mapped; clamped to the
// texel centres again here). Throws engine::Error on an inconsistent image, a bad channel or
// non-finite coordinates.
double sample_unclamped(const GradientImage& low, double u, double v, int channel, plugin_msgs::Upscaler method);

}  // namespace splat_lod::upscale
