// The CPU reference upscalers of docs/algorithms.md §5 (GL-free, double precision inside): the gradient-
// aware spline (Niedermayr et al. Eqs. 25–28 / appendix G Hermite patch on analytic derivatives) and the
// baselines it is compared with (bicubic, bilinear, Lanczos-3). The GPU upscale pass is tested
// against these.
#include "splat_lod/core/upscale.h"

#include <array>
#include <numbers>
#include <string>

#include "engine/core/error.h"

namespace splat_lod::upscale {
namespace {

using plugin_msgs::Upscaler;

// One axis of a sample: the two texels of the cell it falls in and the offset t ∈ [0, 1] from the
// first. The cell is the last one for samples on the last texel centre (t = 1), so i1 = i0 + 1
// whenever the image has two texels or more; a one-texel axis has i0 = i1 = 0 and t = 0.
struct AxisSample {
    int i0 = 0;
    int i1 = 0;
    double t = 0.0;
};

// `u` clamped to the texel centres [0, size − 1]; written so that a NaN lands on 0.
AxisSample axis_sample(double u, int size) {
    const double last = size - 1.0;
    u = u > 0.0 ? std::min(u, last) : 0.0;
    const int i0 = size > 1 ? std::min(static_cast<int>(std::floor(u)), size - 2) : 0;
    return {i0, std::min(i0 + 1, size - 1), u - i0};
}

// Output pixel centre x + 0.5 in output pixels → low-resolution texel-centre coordinate.
double output_to_low(int x, double render_scale) {
    return (x + 0.5) * render_scale - 0.5;
}

int clamp_index(int i, int size) {
    return std::clamp(i, 0, size - 1);
}

// Reads one channel of a per-texel plane with the indices clamped to the image, which extends the
// image as a constant beyond its border (the same rule as the coordinate clamp).
struct Plane {
    const std::vector<float>& data;
    int width;
    int height;
    int channel;

    double operator()(int x, int y) const {
        const std::size_t i = 4 * (static_cast<std::size_t>(clamp_index(y, height)) * static_cast<std::size_t>(width) +
                                   static_cast<std::size_t>(clamp_index(x, width)));
        return data[i + static_cast<std::size_t>(channel)];
    }
};

// [1 t t² t³] · M with M = [[1,0,0,0], [0,0,1,0], [−3,3,−2,−1], [2,−2,1,1]] (docs/algorithms.md §5, the
// inverse of Niedermayr et al.'s C, Eq. 28): the weights of f(0), f(1), f'(0), f'(1).
std::array<double, 4> hermite_weights(double t) {
    const double t2 = t * t, t3 = t2 * t;
    return {1.0 - 3.0 * t2 + 2.0 * t3, 3.0 * t2 - 2.0 * t3, t - 2.0 * t2 + t3, t3 - t2};
}

// The four corners' values and derivatives laid out as Niedermayr et al.'s F (Eq. 27): rows f(0,·),
// f(1,·), fx(0,·), fx(1,·); columns (·,0), (·,1), ∂y(·,0), ∂y(·,1).
using PatchMatrix = std::array<std::array<double, 4>, 4>;

// p(t, s) = [1 t t² t³] M F Mᵀ [1 s s² s³]ᵀ.
double hermite_patch(const PatchMatrix& f, double tx, double ty) {
    const std::array<double, 4> wx = hermite_weights(tx), wy = hermite_weights(ty);
    double sum = 0.0;
    for (std::size_t a = 0; a < 4; ++a) {
        double row = 0.0;
        for (std::size_t b = 0; b < 4; ++b) row += f[a][b] * wy[b];
        sum += wx[a] * row;
    }
    return sum;
}

// Fills F from four accessors giving f, fx, fy and fxy at a texel.
template <typename Value, typename Dx, typename Dy, typename Dxy>
PatchMatrix patch_matrix(const AxisSample& ax, const AxisSample& ay, const Value& f, const Dx& fx, const Dy& fy,
                         const Dxy& fxy) {
    PatchMatrix m;
    const std::array<int, 2> xs{ax.i0, ax.i1}, ys{ay.i0, ay.i1};
    for (std::size_t a = 0; a < 2; ++a)
        for (std::size_t b = 0; b < 2; ++b) {
            m[a][b] = f(xs[a], ys[b]);
            m[a][b + 2] = fy(xs[a], ys[b]);
            m[a + 2][b] = fx(xs[a], ys[b]);
            m[a + 2][b + 2] = fxy(xs[a], ys[b]);
        }
    return m;
}

// Gradient-aware spline: the analytic derivatives are per low-resolution texel, the patch's own
// unit, so they enter F unscaled.
double spline_sample(const GradientImage& low, const AxisSample& ax, const AxisSample& ay, int channel) {
    const Plane f{low.value, low.width, low.height, channel}, fx{low.dx, low.width, low.height, channel};
    const Plane fy{low.dy, low.width, low.height, channel}, fxy{low.dxy, low.width, low.height, channel};
    return hermite_patch(patch_matrix(ax, ay, f, fx, fy, fxy), ax.t, ay.t);
}

// The same patch on central differences, with a true mixed difference for fxy. Hermite with
// slopes (f[i+1] − f[i−1])/2 is Catmull–Rom, i.e. Keys' cubic convolution with a = −0.5, and with
// this fxy the patch is exactly the tensor product of the two 1D kernels: bicubic = Keys(−0.5) in
// x and y wherever the 4×4 neighbourhood is inside the image (and with clamped indices elsewhere).
double bicubic_sample(const GradientImage& low, const AxisSample& ax, const AxisSample& ay, int channel) {
    const Plane f{low.value, low.width, low.height, channel};
    const auto fx = [&](int x, int y) { return 0.5 * (f(x + 1, y) - f(x - 1, y)); };
    const auto fy = [&](int x, int y) { return 0.5 * (f(x, y + 1) - f(x, y - 1)); };
    const auto fxy = [&](int x, int y) {
        return 0.25 * (f(x + 1, y + 1) - f(x + 1, y - 1) - f(x - 1, y + 1) + f(x - 1, y - 1));
    };
    return hermite_patch(patch_matrix(ax, ay, f, fx, fy, fxy), ax.t, ay.t);
}

double bilinear_sample(const GradientImage& low, const AxisSample& ax, const AxisSample& ay, int channel) {
    const Plane f{low.value, low.width, low.height, channel};
    const double top = f(ax.i0, ay.i0) + ax.t * (f(ax.i1, ay.i0) - f(ax.i0, ay.i0));
    const double bottom = f(ax.i0, ay.i1) + ax.t * (f(ax.i1, ay.i1) - f(ax.i0, ay.i1));
    return top + ay.t * (bottom - top);
}

double sinc(double x) {
    if (std::abs(x) < 1e-8) return 1.0;
    const double px = std::numbers::pi * x;
    return std::sin(px) / px;
}

// Taps i0 − 2 … i0 + 3 at distances t + 2 … t − 3, weights sinc(x)·sinc(x/3) for |x| < 3,
// normalised to sum to 1 (the raw weights do not, so a constant image would otherwise ripple).
std::array<double, 6> lanczos3_weights(double t) {
    std::array<double, 6> w{};
    double sum = 0.0;
    for (std::size_t k = 0; k < 6; ++k) {
        const double x = t - (static_cast<double>(k) - 2.0);
        w[k] = std::abs(x) < 3.0 ? sinc(x) * sinc(x / 3.0) : 0.0;
        sum += w[k];
    }
    for (double& weight : w) weight /= sum;  // sum ≥ 1 − small for t ∈ [0, 1]: never 0
    return w;
}

double lanczos3_sample(const GradientImage& low, const AxisSample& ax, const AxisSample& ay, int channel) {
    const Plane f{low.value, low.width, low.height, channel};
    const std::array<double, 6> wx = lanczos3_weights(ax.t), wy = lanczos3_weights(ay.t);
    double sum = 0.0;
    for (std::size_t b = 0; b < 6; ++b) {
        double row = 0.0;
        for (std::size_t a = 0; a < 6; ++a)
            row += wx[a] * f(ax.i0 - 2 + static_cast<int>(a), ay.i0 - 2 + static_cast<int>(b));
        sum += wy[b] * row;
    }
    return sum;
}

double sample(const GradientImage& low, const AxisSample& ax, const AxisSample& ay, int channel, Upscaler method) {
    switch (method) {
        case Upscaler::spline:
            return spline_sample(low, ax, ay, channel);
        case Upscaler::bicubic:
            return bicubic_sample(low, ax, ay, channel);
        case Upscaler::bilinear:
            return bilinear_sample(low, ax, ay, channel);
        case Upscaler::lanczos3:
            return lanczos3_sample(low, ax, ay, channel);
    }
    engine::fail("splat_lod::upscale: invalid upscaler " + std::to_string(static_cast<int>(method)));
}

// Everything the samplers index without further checks.
void check_image(const GradientImage& low, Upscaler method, const std::string& caller) {
    const auto bad = [&](const std::string& what) { engine::fail(caller + ": " + what); };
    if (plugin_msgs::to_string(method) == "<invalid>")
        bad("invalid upscaler " + std::to_string(static_cast<int>(method)));
    if (low.width <= 0 || low.height <= 0)
        bad("low-resolution image is " + std::to_string(low.width) + "x" + std::to_string(low.height));
    const std::size_t size = 4 * static_cast<std::size_t>(low.width) * static_cast<std::size_t>(low.height);
    if (low.value.size() != size)
        bad("low-resolution image is " + std::to_string(low.width) + "x" + std::to_string(low.height) + " but has " +
            std::to_string(low.value.size()) + " values, expected " + std::to_string(size));
    if (method == Upscaler::spline && (low.dx.size() != size || low.dy.size() != size || low.dxy.size() != size))
        bad("the spline needs dx, dy and dxy of " + std::to_string(size) + " values each, got " +
            std::to_string(low.dx.size()) + ", " + std::to_string(low.dy.size()) + ", " +
            std::to_string(low.dxy.size()) + " (render with gradients)");
}

}  // namespace

Rgba32f upscale_image(const GradientImage& low, int out_width, int out_height, double render_scale, Upscaler method) {
    const std::string caller = "splat_lod::upscale::upscale_image()";
    if (!(render_scale > 0.0 && render_scale <= 1.0))
        engine::fail(caller + ": render scale must be in (0, 1], got " + std::to_string(render_scale));
    if (out_width <= 0 || out_height <= 0)
        engine::fail(caller + ": output size must be positive, got " + std::to_string(out_width) + "x" +
                     std::to_string(out_height));
    const int expected_width = low_res_size(out_width, render_scale);
    const int expected_height = low_res_size(out_height, render_scale);
    if (low.width != expected_width || low.height != expected_height)
        engine::fail(caller + ": low-resolution image is " + std::to_string(low.width) + "x" +
                     std::to_string(low.height) + ", expected " + std::to_string(expected_width) + "x" +
                     std::to_string(expected_height) + " for " + std::to_string(out_width) + "x" +
                     std::to_string(out_height) + " at render scale " + std::to_string(render_scale));
    check_image(low, method, caller);

    std::vector<AxisSample> columns(static_cast<std::size_t>(out_width)), rows(static_cast<std::size_t>(out_height));
    for (int x = 0; x < out_width; ++x)
        columns[static_cast<std::size_t>(x)] = axis_sample(output_to_low(x, render_scale), low.width);
    for (int y = 0; y < out_height; ++y)
        rows[static_cast<std::size_t>(y)] = axis_sample(output_to_low(y, render_scale), low.height);

    Rgba32f out;
    out.width = out_width;
    out.height = out_height;
    out.rgba.resize(4 * static_cast<std::size_t>(out_width) * static_cast<std::size_t>(out_height));
    std::size_t i = 0;
    for (const AxisSample& ay : rows)
        for (const AxisSample& ax : columns)
            for (int c = 0; c < 4; ++c) {
                // The cubic methods overshoot next to steep edges (docs/algorithms.md §5: up to ~0.3 for the
                // spline); this clamp is the only limiter. Written so that a NaN, which only
                // non-finite input can produce, becomes 0 rather than reaching the screen.
                const double v = sample(low, ax, ay, c, method);
                out.rgba[i++] = static_cast<float>(v > 0.0 ? std::min(v, 1.0) : 0.0);
            }
    return out;
}

double sample_unclamped(const GradientImage& low, double u, double v, int channel, Upscaler method) {
    const std::string caller = "splat_lod::upscale::sample_unclamped()";
    check_image(low, method, caller);
    if (channel < 0 || channel > 3) engine::fail(caller + ": channel must be 0–3, got " + std::to_string(channel));
    if (!std::isfinite(u) || !std::isfinite(v)) engine::fail(caller + ": sample coordinates must be finite");
    return sample(low, axis_sample(u, low.width), axis_sample(v, low.height), channel, method);
}

}  // namespace splat_lod::upscale
