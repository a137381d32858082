#include "splat_lod/eval/image_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "engine/core/error.h"

namespace splat_lod::eval {
namespace {

constexpr int kWindow = 11;
constexpr double kSigma = 1.5;

void check_same_size(const FloatImage& a, const FloatImage& b, const char* function) {
    if (a.width != b.width || a.height != b.height)
        engine::fail(std::string("splat_lod::eval::") + function +
                     "(): image sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
                     std::to_string(b.width) + "x" + std::to_string(b.height));
}

std::array<double, kWindow> gaussian_weights() {
    std::array<double, kWindow> w{};
    double sum = 0.0;
    for (int i = 0; i < kWindow; ++i) {
        const double x = i - kWindow / 2;
        w[static_cast<std::size_t>(i)] = std::exp(-x * x / (2.0 * kSigma * kSigma));
        sum += w[static_cast<std::size_t>(i)];
    }
    for (auto& v : w) v /= sum;
    return w;
}

// The five windowed moments of one channel at one window origin, with the window clipped to the
// image (only matters for images smaller than the window).
struct Moments {
    double mean_a = 0, mean_b = 0, aa = 0, bb = 0, ab = 0;
};

Moments window_moments(const FloatImage& a, const FloatImage& b, int c, int x0, int y0,
                       const std::array<double, kWindow>& w) {
    Moments m;
    double total = 0.0;
    for (int dy = 0; dy < kWindow; ++dy) {
        const int y = y0 + dy;
        if (y < 0 || y >= a.height) continue;
        for (int dx = 0; dx < kWindow; ++dx) {
            const int x = x0 + dx;
            if (x < 0 || x >= a.width) continue;
            const double weight = w[static_cast<std::size_t>(dy)] * w[static_cast<std::size_t>(dx)];
            const double va = a.at(x, y, c), vb = b.at(x, y, c);
            total += weight;
            m.mean_a += weight * va;
            m.mean_b += weight * vb;
            m.aa += weight * va * va;
            m.bb += weight * vb * vb;
            m.ab += weight * va * vb;
        }
    }
    m.mean_a /= total;
    m.mean_b /= total;
    m.aa /= total;
    m.bb /= total;
    m.ab /= total;
    return m;
}

double ssim_of(const Moments& m) {
    constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    const double var_a = m.aa - m.mean_a * m.mean_a, var_b = m.bb - m.mean_b * m.mean_b;
    const double cov = m.ab - m.mean_a * m.mean_b;
    return ((2 * m.mean_a * m.mean_b + c1) * (2 * cov + c2)) /
           ((m.mean_a * m.mean_a + m.mean_b * m.mean_b + c1) * (var_a + var_b + c2));
}

}  // namespace

FloatImage make_float_image(int width, int height, float value) {
    FloatImage image;
    image.width = width;
    image.height = height;
    image.rgb.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, value);
    return image;
}

FloatImage to_float(const engine::Image& image) {
    FloatImage out = make_float_image(image.width, image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(image.pixel(x, y)[c]) / 255.0f;
    return out;
}

engine::Image to_rgba8(const FloatImage& image) {
    engine::Image out{image.width, image.height, {}};
    out.rgba.assign(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4, 255);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c)
                out.pixel(x, y)[c] =
                    static_cast<std::uint8_t>(std::lround(std::clamp(image.at(x, y, c), 0.0f, 1.0f) * 255.0f));
    return out;
}

double psnr(const FloatImage& a, const FloatImage& b) {
    check_same_size(a, b, "psnr");
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const double d = static_cast<double>(a.rgb[i]) - static_cast<double>(b.rgb[i]);
        sum += d * d;
    }
    if (sum == 0.0) return std::numeric_limits<double>::infinity();
    return -10.0 * std::log10(sum / static_cast<double>(a.rgb.size()));
}

double ssim(const FloatImage& a, const FloatImage& b) {
    check_same_size(a, b, "ssim");
    if (a.width == 0 || a.height == 0) engine::fail("splat_lod::eval::ssim(): empty image");
    const auto w = gaussian_weights();
    // Valid windows only; an image smaller than the window gets the single clipped window at 0.
    const int last_x = std::max(0, a.width - kWindow), last_y = std::max(0, a.height - kWindow);
    double sum = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int y0 = 0; y0 <= last_y; ++y0)
            for (int x0 = 0; x0 <= last_x; ++x0) sum += ssim_of(window_moments(a, b, c, x0, y0, w));
    return sum / (3.0 * static_cast<double>(last_x + 1) * static_cast<double>(last_y + 1));
}

void check_scale(int k, int width, int height, const std::string& what) {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (k < 1) engine::fail(what + ": scale " + std::to_string(k) + " is not a positive integer");
    if (k > width || k > height)
        engine::fail(what + ": scale " + std::to_string(k) + " is larger than the image " + size);
    if (width % k != 0 || height % k != 0)
        engine::fail(what + ": scale " + std::to_string(k) + " does not divide the image size " + size);
}

FloatImage area_average(const FloatImage& image, int k) {
    check_scale(k, image.width, image.height, "splat_lod::eval::area_average()");
    FloatImage out = make_float_image(image.width / k, image.height / k);
    const double inv = 1.0 / (static_cast<double>(k) * k);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0.0;
                for (int dy = 0; dy < k; ++dy)
                    for (int dx = 0; dx < k; ++dx) sum += image.at(x * k + dx, y * k + dy, c);
                out.at(x, y, c) = static_cast<float>(sum * inv);
            }
    return out;
}

}  // namespace splat_lod::eval
