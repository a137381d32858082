// The CPU reference upscalers (docs/algorithms.md §5): what each interpolant reproduces exactly, the
// output-to-texel mapping for integer and fractional factors, and the hard cases (a one-pixel-wide
// Gaussian, 1×1 and 4096-wide targets, huge derivatives, bad input).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/upscale.h"
#include "splat_reference_test_helpers.h"

namespace up = splat_lod::upscale;
namespace ref = splat_lod::reference;
using plugin_msgs::Upscaler;

namespace {

constexpr std::array<Upscaler, 4> kAllMethods{Upscaler::spline, Upscaler::bicubic, Upscaler::bilinear,
                                              Upscaler::lanczos3};

// f(x, y, channel) and its derivatives at texel centres (x, y integers).
using Field = std::function<double(double, double, int)>;

up::GradientImage make_image(int width, int height, const Field& value, const Field& dx = {}, const Field& dy = {},
                             const Field& dxy = {}) {
    up::GradientImage image;
    image.width = width;
    image.height = height;
    const auto fill = [&](std::vector<float>& plane, const Field& f) {
        if (!f) return;
        plane.resize(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                for (int c = 0; c < 4; ++c)
                    plane[image.texel(x, y) + static_cast<std::size_t>(c)] = static_cast<float>(f(x, y, c));
    };
    fill(image.value, value);
    fill(image.dx, dx);
    fill(image.dy, dy);
    fill(image.dxy, dxy);
    return image;
}

// Uniform noise in [lo, hi], a fixed function of (x, y, channel, seed).
Field noise(unsigned seed, double lo, double hi) {
    return [=](double x, double y, int c) {
        std::mt19937 rng(seed * 7919u + static_cast<unsigned>(x) * 131u + static_cast<unsigned>(y) * 17u +
                         static_cast<unsigned>(c));
        return std::uniform_real_distribution<double>(lo, hi)(rng);
    };
}

// P(x, y) = offset + Σ_{i,j ≤ degree} a_ij (x/w)^i (y/h)^j per channel, with its exact derivatives:
// a bicubic (degree 3), biquadratic (2) or bilinear (1) polynomial of the texel coordinates.
struct Polynomial {
    int degree = 3;
    double w = 1.0, h = 1.0, offset = 0.0;
    std::array<std::array<std::array<double, 4>, 4>, 4> a{};  // [channel][i][j]

    Polynomial(int degree_, double w_, double h_, double amplitude, double offset_, unsigned seed)
        : degree(degree_), w(w_), h(h_), offset(offset_) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(-amplitude, amplitude);
        for (auto& channel : a)
            for (int i = 0; i <= degree; ++i)
                for (int j = 0; j <= degree; ++j)
                    channel[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = u(rng);
    }

    // ∂^(nx+ny) P / ∂x^nx ∂y^ny for nx, ny ∈ {0, 1}.
    double eval(double x, double y, int c, int nx, int ny) const {
        const double X = x / w, Y = y / h;
        double sum = (nx == 0 && ny == 0) ? offset : 0.0;
        for (int i = nx; i <= degree; ++i)
            for (int j = ny; j <= degree; ++j) {
                const double coeff =
                    a[static_cast<std::size_t>(c)][static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
                sum += coeff * (nx ? i / w : 1.0) * std::pow(X, i - nx) * (ny ? j / h : 1.0) * std::pow(Y, j - ny);
            }
        return sum;
    }
    Field value() const {
        return [this](double x, double y, int c) { return eval(x, y, c, 0, 0); };
    }
    Field dx() const {
        return [this](double x, double y, int c) { return eval(x, y, c, 1, 0); };
    }
    Field dy() const {
        return [this](double x, double y, int c) { return eval(x, y, c, 0, 1); };
    }
    Field dxy() const {
        return [this](double x, double y, int c) { return eval(x, y, c, 1, 1); };
    }
    up::GradientImage image(int width, int height) const {
        return make_image(width, height, value(), dx(), dy(), dxy());
    }
};

// upscale.h's mapping, written out here: output pixel → texel-centre coordinate, clamped.
double mapped(int x, double s, int low_side) {
    return std::clamp((x + 0.5) * s - 0.5, 0.0, low_side - 1.0);
}

float out_at(const up::Rgba32f& image, int x, int y, int c) {
    const std::size_t pixel =
        static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x);
    return image.rgba[4 * pixel + static_cast<std::size_t>(c)];
}

::testing::AssertionResult finite_in_unit_range(const up::Rgba32f& image) {
    if (image.rgba.size() != 4 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
        return ::testing::AssertionFailure() << "output has " << image.rgba.size() << " floats";
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
        if (!(image.rgba[i] >= 0.0f && image.rgba[i] <= 1.0f))
            return ::testing::AssertionFailure() << "output value " << i << " is " << image.rgba[i];
    return ::testing::AssertionSuccess();
}

// Keys' cubic convolution kernel (Keys 1981) with a = −0.5.
double keys(double x) {
    const double a = -0.5, t = std::abs(x);
    if (t <= 1.0) return ((a + 2.0) * t - (a + 3.0)) * t * t + 1.0;
    if (t < 2.0) return ((a * t - 5.0 * a) * t + 8.0 * a) * t - 4.0 * a;
    return 0.0;
}

// Direct 4×4 Keys convolution at (u, v) with clamped indices.
double keys_sample(const up::GradientImage& image, double u, double v, int c) {
    const int i = static_cast<int>(std::floor(u)), j = static_cast<int>(std::floor(v));
    double sum = 0.0;
    for (int y = j - 1; y <= j + 2; ++y)
        for (int x = i - 1; x <= i + 2; ++x) {
            const int cx = std::clamp(x, 0, image.width - 1), cy = std::clamp(y, 0, image.height - 1);
            sum += keys(u - x) * keys(v - y) * image.value[image.texel(cx, cy) + static_cast<std::size_t>(c)];
        }
    return sum;
}

}  // namespace

TEST(Upscale, LowResSizeRoundsUpAndSurvivesFloatRounding) {
    EXPECT_EQ(up::low_res_size(1920, 1.0 / 3.0), 640);
    EXPECT_EQ(up::low_res_size(1920, static_cast<float>(1.0 / 3.0)), 640);
    EXPECT_EQ(up::low_res_size(37, 1.0 / 3.0), 13);
    EXPECT_EQ(up::low_res_size(1, 0.01), 1);
    EXPECT_EQ(up::low_res_size(4096, 1.0 / 3.0), 1366);
}

TEST(Upscale, FactorOneIsTheIdentityForEveryMethod) {
    const int w = 9, h = 7;
    const auto low =
        make_image(w, h, noise(1, 0.0, 1.0), noise(2, -3.0, 3.0), noise(3, -3.0, 3.0), noise(4, -9.0, 9.0));
    for (const Upscaler method : kAllMethods) {
        const auto out = up::upscale_image(low, w, h, 1.0, method);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 4; ++c) {
                    const float expected = low.value[low.texel(x, y) + static_cast<std::size_t>(c)];
                    if (method == Upscaler::lanczos3)  // sin(kπ) is ~1e−16, not 0, in double
                        EXPECT_NEAR(out_at(out, x, y, c), expected, 1e-6f);
                    else
                        EXPECT_EQ(out_at(out, x, y, c), expected) << plugin_msgs::to_string(method);
                }
    }
}

// At factors 3 and 5 the output pixels 3k + 1 (5k + 2) sit on texel centres: every method is an
// interpolant, and the spline's derivatives (random here) must not leak into those samples.
TEST(Upscale, SplineAndBaselinesHitTexelCentresAtOddIntegerFactors) {
    const int w = 7, h = 5;
    const auto low =
        make_image(w, h, noise(5, 0.0, 1.0), noise(6, -2.0, 2.0), noise(7, -2.0, 2.0), noise(8, -5.0, 5.0));
    for (const int factor : {3, 5}) {
        const double s = 1.0 / factor;
        for (const Upscaler method : kAllMethods) {
            const auto out = up::upscale_image(low, factor * w, factor * h, s, method);
            ASSERT_TRUE(finite_in_unit_range(out));
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x)
                    for (int c = 0; c < 4; ++c)
                        EXPECT_NEAR(out_at(out, factor * x + factor / 2, factor * y + factor / 2, c),
                                    low.value[low.texel(x, y) + static_cast<std::size_t>(c)], 1e-6)
                            << plugin_msgs::to_string(method) << " factor " << factor << " texel " << x << "," << y;
        }
    }
}

// Given a bicubic polynomial's exact values and derivatives at the texel centres, the spline is
// that polynomial everywhere in the hull of the centres (the Hermite patch is exact on bicubics).
// Inputs are stored as float (relative error 6e−8) and the patch weights sum in absolute value to
// at most (1 + 0.3)² ≈ 1.7, so the tolerance is 4e−7 × (1 + max|P|, max|∂P|).
TEST(Upscale, SplineReproducesBicubicPolynomials) {
    const int w = 8, h = 6;
    const Polynomial p(3, w, h, 1.0, 0.0, 11);
    const auto low = p.image(w, h);
    std::mt19937 rng(12);
    std::uniform_real_distribution<double> ux(0.0, w - 1.0), uy(0.0, h - 1.0);
    double worst = 0.0;
    for (int n = 0; n < 400; ++n) {
        const double u = ux(rng), v = uy(rng);
        for (int c = 0; c < 4; ++c) {
            const double expected = p.eval(u, v, c, 0, 0);
            const double got = up::sample_unclamped(low, u, v, c, Upscaler::spline);
            EXPECT_NEAR(got, expected, 4e-7 * 20.0) << "at " << u << "," << v;
            worst = std::max(worst, std::abs(got - expected));
        }
    }
    // Corners and edges of the hull, where the cell index is clamped (i ≤ w − 2).
    for (const double u : {0.0, w - 1.0, 3.0})
        for (const double v : {0.0, h - 1.0, 2.5})
            EXPECT_NEAR(up::sample_unclamped(low, u, v, 2, Upscaler::spline), p.eval(u, v, 2, 0, 0), 4e-7 * 20.0);
    std::printf("[ measured ] spline vs bicubic polynomial: max error %.3g\n", worst);
    // Teeth: with the derivatives zeroed the patch is not exact on this polynomial.
    auto flat = low;
    std::fill(flat.dx.begin(), flat.dx.end(), 0.0f);
    EXPECT_GT(std::abs(up::sample_unclamped(flat, 2.5, 2.5, 0, Upscaler::spline) - p.eval(2.5, 2.5, 0, 0, 0)), 1e-4);
}

// Central differences are exact on quadratics, so the bicubic baseline reproduces biquadratics
// wherever its 4×4 neighbourhood is inside the image (u ∈ [1, w − 2]); at the border the clamped
// neighbours make the slopes one-sided and it does not.
TEST(Upscale, BicubicReproducesQuadraticsInTheInterior) {
    const int w = 9, h = 8;
    const Polynomial p(2, w, h, 1.0, 0.0, 21);
    const auto low = make_image(w, h, p.value());
    std::mt19937 rng(22);
    std::uniform_real_distribution<double> ux(1.0, w - 2.0), uy(1.0, h - 2.0);
    for (int n = 0; n < 400; ++n) {
        const double u = ux(rng), v = uy(rng);
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(up::sample_unclamped(low, u, v, c, Upscaler::bicubic), p.eval(u, v, c, 0, 0), 4e-6);
    }
}

// bicubic = Keys' kernel with a = −0.5 (a tensor product, so the mixed difference must be the true
// one): in the interior, and with the same clamped indices at the border too.
TEST(Upscale, BicubicEqualsKeysCubicConvolution) {
    const int w = 10, h = 7;
    const auto low = make_image(w, h, noise(31, 0.0, 1.0));
    std::mt19937 rng(32);
    for (const bool interior : {true, false}) {
        std::uniform_real_distribution<double> ux(interior ? 1.0 : 0.0, interior ? w - 2.0 : w - 1.0);
        std::uniform_real_distribution<double> uy(interior ? 1.0 : 0.0, interior ? h - 2.0 : h - 1.0);
        for (int n = 0; n < 300; ++n) {
            const double u = ux(rng), v = uy(rng);
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(up::sample_unclamped(low, u, v, c, Upscaler::bicubic), keys_sample(low, u, v, c), 1e-12)
                    << (interior ? "interior " : "anywhere ") << u << "," << v;
        }
    }
}

TEST(Upscale, BilinearReproducesBilinearFunctions) {
    const int w = 6, h = 9;
    const Polynomial p(1, w, h, 1.0, 0.0, 41);
    const auto low = make_image(w, h, p.value());
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> ux(0.0, w - 1.0), uy(0.0, h - 1.0);
    for (int n = 0; n < 400; ++n) {
        const double u = ux(rng), v = uy(rng);
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(up::sample_unclamped(low, u, v, c, Upscaler::bilinear), p.eval(u, v, c, 0, 0), 1e-6);
    }
}

// Normalised weights: a constant image stays constant everywhere, borders included.
TEST(Upscale, Lanczos3ReproducesConstantsAndTexelValues) {
    const auto constant = make_image(6, 4, [](double, double, int c) { return 0.2 + 0.2 * c; });
    const auto out = up::upscale_image(constant, 13, 10, 1.0 / 2.5, Upscaler::lanczos3);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 4; ++c) EXPECT_NEAR(out_at(out, x, y, c), 0.2 + 0.2 * c, 1e-6);
    const auto low = make_image(6, 5, noise(51, 0.0, 1.0));
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 6; ++x)
            EXPECT_NEAR(up::sample_unclamped(low, x, y, 1, Upscaler::lanczos3), low.value[low.texel(x, y) + 1], 1e-9);
    // Between centres it is not the bilinear value (the check above is not vacuous).
    EXPECT_GT(std::abs(up::sample_unclamped(low, 2.5, 2.5, 1, Upscaler::lanczos3) -
                       up::sample_unclamped(low, 2.5, 2.5, 1, Upscaler::bilinear)),
              1e-4);
}

// Output pixel (x, y) samples u = (x + 0.5)·s − 0.5 (clamped) for fractional factors and odd
// sizes: checked through polynomials each method reproduces (values kept inside [0, 1] so the
// final clamp does not interfere).
TEST(Upscale, FractionalFactorsAndOddSizesFollowTheMapping) {
    for (const double factor : {1.5, 2.5, 3.0, 3.7}) {
        const double s = 1.0 / factor;
        const int out_w = 37, out_h = 23;
        const int w = up::low_res_size(out_w, s), h = up::low_res_size(out_h, s);
        const Polynomial cubic(3, w, h, 0.02, 0.5, 61);
        const Polynomial linear(1, w, h, 0.1, 0.5, 62);
        const auto spline = up::upscale_image(cubic.image(w, h), out_w, out_h, s, Upscaler::spline);
        const auto bilinear = up::upscale_image(make_image(w, h, linear.value()), out_w, out_h, s, Upscaler::bilinear);
        ASSERT_EQ(spline.width, out_w);
        ASSERT_EQ(spline.height, out_h);
        for (int y = 0; y < out_h; ++y)
            for (int x = 0; x < out_w; ++x) {
                const double u = mapped(x, s, w), v = mapped(y, s, h);
                for (int c = 0; c < 4; ++c) {
                    EXPECT_NEAR(out_at(spline, x, y, c), cubic.eval(u, v, c, 0, 0), 1e-6) << "factor " << factor;
                    EXPECT_NEAR(out_at(bilinear, x, y, c), linear.eval(u, v, c, 0, 0), 1e-6) << "factor " << factor;
                }
            }
        for (const Upscaler method : kAllMethods)
            EXPECT_TRUE(finite_in_unit_range(up::upscale_image(cubic.image(w, h), out_w, out_h, s, method)));
    }
}

// A 4096×2 target at s = 1/3 has a 1366×1 source: one texel row (v clamps to 0, t_y = 0).
TEST(Upscale, WideTargetWithASingleSourceRow) {
    const int out_w = 4096, out_h = 2;
    const double s = 1.0 / 3.0;
    const int w = up::low_res_size(out_w, s), h = up::low_res_size(out_h, s);
    ASSERT_EQ(w, 1366);
    ASSERT_EQ(h, 1);
    const Polynomial cubic(3, w, 1.0, 0.02, 0.5, 71);
    const auto low = cubic.image(w, h);
    for (const Upscaler method : kAllMethods) {
        const auto out = up::upscale_image(low, out_w, out_h, s, method);
        ASSERT_TRUE(finite_in_unit_range(out)) << plugin_msgs::to_string(method);
    }
    const auto out = up::upscale_image(low, out_w, out_h, s, Upscaler::spline);
    for (int y = 0; y < out_h; ++y)
        for (int x = 0; x < out_w; x += 7)
            EXPECT_NEAR(out_at(out, x, y, 0), cubic.eval(mapped(x, s, w), 0.0, 0, 0, 0), 1e-6) << x;
}

// A 1×1 target (and a 1×1 source stretched to 3×3): a single texel, whatever its derivatives.
TEST(Upscale, SingleTexelSourcesAndTargets) {
    const std::array<double, 4> value{0.2, 0.4, 1.5, -0.3};
    const auto low = make_image(
        1, 1, [&](double, double, int c) { return value[static_cast<std::size_t>(c)]; },
        [](double, double, int) { return 1e30; }, [](double, double, int) { return -1e30; },
        [](double, double, int) { return 1e30; });
    const std::array<float, 4> expected{0.2f, 0.4f, 1.0f, 0.0f};
    for (const Upscaler method : kAllMethods)
        for (const auto& [size, s] : {std::pair{1, 1.0}, std::pair{1, 0.5}, std::pair{3, 1.0 / 3.0}}) {
            const auto out = up::upscale_image(low, size, size, s, method);
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x)
                    for (int c = 0; c < 4; ++c)
                        EXPECT_NEAR(out_at(out, x, y, c), expected[static_cast<std::size_t>(c)], 1e-7)
                            << plugin_msgs::to_string(method) << " " << size << "x" << size;
        }
}

// Derivatives at float's limits, infinite or NaN: no NaN and nothing outside [0, 1] reaches the
// output, and no read leaves the image.
TEST(Upscale, HugeAndNonFiniteDerivativesStayInRange) {
    const float big = std::numeric_limits<float>::max();
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    for (const float extreme : {big, inf, nan}) {
        const auto low = make_image(
            6, 4, noise(81, 0.0, 1.0),
            [&](double x, double, int) { return (static_cast<int>(x) % 2 ? 1 : -1) * extreme; },
            [&](double, double y, int) { return (static_cast<int>(y) % 2 ? -1 : 1) * extreme; },
            [&](double, double, int) { return extreme; });
        const auto out = up::upscale_image(low, 13, 10, 1.0 / 2.5, Upscaler::spline);
        EXPECT_TRUE(finite_in_unit_range(out)) << extreme;
    }
}

// The largest amount by which the spline leaves the [min, max] of the four corner texels of its
// cell, over every output pixel and channel, before the final clamp.
double spline_overshoot(const up::GradientImage& low, int out_width, int out_height, double s) {
    double overshoot = 0.0;
    for (int y = 0; y < out_height; ++y)
        for (int x = 0; x < out_width; ++x) {
            const double u = mapped(x, s, low.width), v = mapped(y, s, low.height);
            const int i = std::min(static_cast<int>(u), low.width - 2),
                      j = std::min(static_cast<int>(v), low.height - 2);
            for (int c = 0; c < 4; ++c) {
                double lo = std::numeric_limits<double>::infinity(), hi = -lo;
                for (const int cy : {j, j + 1})
                    for (const int cx : {i, i + 1}) {
                        lo = std::min<double>(lo, low.value[low.texel(cx, cy) + static_cast<std::size_t>(c)]);
                        hi = std::max<double>(hi, low.value[low.texel(cx, cy) + static_cast<std::size_t>(c)]);
                    }
                const double p = up::sample_unclamped(low, u, v, c, Upscaler::spline);
                if (!std::isfinite(p)) return std::numeric_limits<double>::infinity();
                overshoot = std::max({overshoot, p - hi, lo - p});
            }
        }
    return overshoot;
}

// docs/algorithms.md §7: spline upscaling of a one-pixel-wide Gaussian. A dot and a line σ = 0.3 low-res
// px across, opacity 0.99, rendered at s = 1/3 with the resolution-consistent dilation 0.3·s² and
// upscaled 3×, at nine sub-texel positions. The output is finite and in [0, 1]. Before the clamp
// the patch leaves the range of its four corner texels by 0.08–0.34 depending on where the dot
// falls between texel centres (measured max 0.342; 0.346 over a 12×12 sweep of positions), much
// of it the real peak between the centres: asserted ≤ 0.45. It must overshoot at all, which it
// would not without the derivatives (the Hermite weights of the values alone are a convex
// combination).
TEST(Upscale, OnePixelWideGaussianHasBoundedSplineOvershoot) {
    namespace t = splat_lod::reference::test;
    const auto full = t::axis_camera(48, 36, 60.0);
    const double s = 1.0 / 3.0;
    const auto low_camera = ref::scaled_camera(full, s);
    ref::ReferenceSettings settings;
    settings.gradients = true;
    settings.dilation = 0.3 * s * s;
    const float sigma = static_cast<float>(0.3 / s * 5.0 / full.fx);  // 0.3 low-res px at z = 5
    const float texel = static_cast<float>(1.0 / s * 5.0 / full.fx);  // one low-res px at z = 5
    double worst = 0.0;
    for (const float ox : {0.0f, 1.0f / 3.0f, 2.0f / 3.0f})
        for (const float oy : {0.0f, 1.0f / 3.0f, 2.0f / 3.0f}) {
            splat_lod::SplatCloud cloud;
            t::add_gaussian(cloud, {0.11f + ox * texel, -0.07f + oy * texel, -5.0f}, std::log(sigma), 0.99, {1, 1, 1});
            const std::size_t line = t::add_gaussian(cloud, {-0.9f + ox * texel, 0.5f + oy * texel, -5.0f},
                                                     std::log(sigma), 0.99, {1, 0.2, 0});
            cloud.log_scales[line].y = std::log(0.8f);  // 9.6 native px long, at 30°
            cloud.rotations[line] = {0.9659258f, 0.0f, 0.0f, 0.2588190f};
            const auto low = ref::to_gradient_image(t::render_cloud(cloud, low_camera, settings));
            ASSERT_TRUE(finite_in_unit_range(up::upscale_image(low, full.width, full.height, s, Upscaler::spline)));
            worst = std::max(worst, spline_overshoot(low, full.width, full.height, s));
        }
    std::printf("[ measured ] spline overshoot beyond the four corner texels: %.4f\n", worst);
    EXPECT_LE(worst, 0.45);
    EXPECT_GT(worst, 0.01);
}

TEST(Upscale, RejectsBadInput) {
    const auto low = make_image(10, 8, noise(91, 0.0, 1.0), noise(92, -1, 1), noise(93, -1, 1), noise(94, -1, 1));
    const auto expect_error = [](const std::function<void()>& call, const std::string& needle) {
        try {
            call();
            ADD_FAILURE() << "no error, expected one mentioning '" << needle << "'";
        } catch (const engine::Error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    expect_error([&] { up::upscale_image(low, 30, 30, 1.0 / 3.0, Upscaler::bilinear); }, "expected 10x10");
    expect_error([&] { up::upscale_image(low, 20, 16, 1.0 / 3.0, Upscaler::spline); }, "expected 7x6");
    for (const double s : {0.0, -1.0, 1.5, std::numeric_limits<double>::quiet_NaN()})
        expect_error([&] { up::upscale_image(low, 10, 8, s, Upscaler::bicubic); }, "render scale");
    expect_error([&] { up::upscale_image(low, 0, 8, 1.0, Upscaler::bicubic); }, "output size");

    auto no_derivatives = low;
    no_derivatives.dx.clear();
    no_derivatives.dy.clear();
    no_derivatives.dxy.clear();
    expect_error([&] { up::upscale_image(no_derivatives, 30, 24, 1.0 / 3.0, Upscaler::spline); }, "spline needs");
    EXPECT_NO_THROW(up::upscale_image(no_derivatives, 30, 24, 1.0 / 3.0, Upscaler::bicubic));
    auto short_dxy = low;
    short_dxy.dxy.pop_back();
    expect_error([&] { up::upscale_image(short_dxy, 30, 24, 1.0 / 3.0, Upscaler::spline); }, "spline needs");
    auto short_values = low;
    short_values.value.resize(12);
    expect_error([&] { up::upscale_image(short_values, 30, 24, 1.0 / 3.0, Upscaler::lanczos3); }, "values");
    expect_error([&] { up::upscale_image(low, 30, 24, 1.0 / 3.0, static_cast<Upscaler>(9)); }, "invalid upscaler");

    expect_error([&] { up::sample_unclamped(low, 1.0, 1.0, 4, Upscaler::bilinear); }, "channel");
    expect_error([&] { up::sample_unclamped(low, std::nan(""), 1.0, 0, Upscaler::bilinear); }, "finite");
    expect_error([&] { up::sample_unclamped(no_derivatives, 1.0, 1.0, 0, Upscaler::spline); }, "spline needs");
    // Coordinates beyond the hull are clamped, never read outside the image.
    EXPECT_EQ(up::sample_unclamped(low, -50.0, 1e9, 0, Upscaler::lanczos3),
              up::sample_unclamped(low, 0.0, 7.0, 0, Upscaler::lanczos3));
}
