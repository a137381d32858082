// png_stats: small image checks for the window test script, so that it needs no Python or
// ImageMagick.
//   png_stats stats IMAGE.png [--min-stddev S]
//       prints "WxH mean M stddev S" (over RGB, 0..255); fails when stddev < S.
//   png_stats diff A.png B.png [--threshold T] [--min-fraction F] [--max-fraction F]
//       prints the share of pixels whose RGB differs by more than T, PSNR and the largest
//       channel difference; fails outside the given share bounds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "engine/core/error.h"
#include "engine/render/image.h"

namespace {

struct Moments {
    double mean = 0.0;
    double stddev = 0.0;
};

Moments rgb_moments(const engine::Image& image) {
    double sum = 0.0, sum_sq = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        if (i % 4 == 3) continue;  // alpha says nothing about what is on screen
        const double v = image.rgba[i];
        sum += v;
        sum_sq += v * v;
        ++n;
    }
    if (n == 0) engine::fail("empty image");
    const double mean = sum / static_cast<double>(n);
    return {mean, std::sqrt(std::max(0.0, sum_sq / static_cast<double>(n) - mean * mean))};
}

int run_stats(const std::filesystem::path& path, double min_stddev) {
    const engine::Image image = engine::read_png(path);
    const Moments m = rgb_moments(image);
    std::printf("%s: %dx%d mean %.2f stddev %.2f\n", path.filename().c_str(), image.width, image.height, m.mean,
                m.stddev);
    if (m.stddev < min_stddev) {
        std::fprintf(stderr, "png_stats: %s is nearly uniform (stddev %.2f < %.2f)\n", path.c_str(), m.stddev,
                     min_stddev);
        return 1;
    }
    return 0;
}

int run_diff(const std::filesystem::path& a, const std::filesystem::path& b, int threshold, double min_fraction,
             double max_fraction) {
    const engine::ImageDifference d = engine::compare_images(engine::read_png(a), engine::read_png(b), threshold);
    std::printf("%s vs %s: %.4f%% of pixels differ by > %d, PSNR %.2f dB, max channel difference %d\n",
                a.filename().c_str(), b.filename().c_str(), 100.0 * d.fraction_over_threshold, threshold, d.psnr_db,
                d.max_channel_difference);
    if (d.fraction_over_threshold < min_fraction || d.fraction_over_threshold > max_fraction) {
        std::fprintf(stderr, "png_stats: differing share %.6f outside [%.6f, %.6f]\n", d.fraction_over_threshold,
                     min_fraction, max_fraction);
        return 1;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Image statistics and comparisons for the window test."};
    app.require_subcommand(1);
    std::filesystem::path image, a, b;
    double min_stddev = 0.0, min_fraction = 0.0, max_fraction = 1.0;
    int threshold = 8;
    CLI::App* stats = app.add_subcommand("stats", "Mean and standard deviation of RGB");
    stats->add_option("image", image)->required()->check(CLI::ExistingFile);
    stats->add_option("--min-stddev", min_stddev, "Fail below this standard deviation");
    CLI::App* diff = app.add_subcommand("diff", "Share of pixels that differ between two images of one size");
    diff->add_option("a", a)->required()->check(CLI::ExistingFile);
    diff->add_option("b", b)->required()->check(CLI::ExistingFile);
    diff->add_option("--threshold", threshold, "RGB difference that counts as different");
    diff->add_option("--min-fraction", min_fraction, "Fail when fewer pixels differ");
    diff->add_option("--max-fraction", max_fraction, "Fail when more pixels differ");
    CLI11_PARSE(app, argc, argv);
    try {
        if (stats->parsed()) return run_stats(image, min_stddev);
        return run_diff(a, b, threshold, min_fraction, max_fraction);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "png_stats: %s\n", e.what());
        return 1;
    }
}
