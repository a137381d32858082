// The upscale sweep's side-by-side crops: the native image's most detailed window, from native and
// each upscaler, one row per crop factor, magnified by nearest neighbour so that the upscalers'
// pixels (and their blur or ringing) are visible.
#include <algorithm>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "splat_lod/eval/eval_report.h"
#include "splat_lod/eval/sheet_drawing.h"
#include "splat_lod/eval/upscale_report.h"

namespace splat_lod::eval {
namespace {

constexpr int kRowLabelWidth = 40;
constexpr int kGap = 2;
constexpr int kSearchStep = 4;

double luma(const engine::Image& image, int x, int y) {
    const std::uint8_t* p = image.pixel(x, y);
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
}

// Summed-area table of the gradient energy: sums[(y)(W+1) + x] is the energy of [0, x) × [0, y).
std::vector<double> energy_sums(const engine::Image& image) {
    const int w = image.width, h = image.height;
    const auto at = [&](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(w + 1) + static_cast<std::size_t>(x);
    };
    std::vector<double> sums(static_cast<std::size_t>(w + 1) * static_cast<std::size_t>(h + 1), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double l = luma(image, x, y);
            const double gx = x + 1 < w ? luma(image, x + 1, y) - l : 0.0;
            const double gy = y + 1 < h ? luma(image, x, y + 1) - l : 0.0;
            sums[at(x + 1, y + 1)] = gx * gx + gy * gy + sums[at(x, y + 1)] + sums[at(x + 1, y)] - sums[at(x, y)];
        }
    return sums;
}

const engine::Image* find_tile(const std::vector<ContactTile>& tiles, const std::string& method, int factor) {
    for (const auto& tile : tiles)
        if (tile.method == method && tile.factor == factor) return &tile.image;
    return nullptr;
}

// "spline 41.23 dB": the first view's PSNR of the whole image against native.
std::string tile_label(const EvalResults& results, const std::string& method, int factor) {
    for (const auto& row : results.rows)
        if (row.sweep == Sweep::upscale && row.view == 0 && row.method == method && row.factor == factor)
            return method == "native" ? method : method + ' ' + format_db(row.psnr) + " dB";
    return method;
}

void draw_crop(engine::Image& sheet, const engine::Image& image, const CropWindow& w, int x0, int y0) {
    for (int y = 0; y < w.height * kCropMagnification; ++y)
        for (int x = 0; x < w.width * kCropMagnification; ++x)
            std::copy_n(image.pixel(w.x + x / kCropMagnification, w.y + y / kCropMagnification), 3,
                        sheet.pixel(x0 + x, y0 + y));
}

}  // namespace

CropWindow detail_window(const engine::Image& image, int side) {
    if (image.width < 1 || image.height < 1 || side < 1)
        engine::fail("splat_lod::eval::detail_window(): empty image or window");
    CropWindow best{0, 0, std::min(side, image.width), std::min(side, image.height)};
    const std::vector<double> sums = energy_sums(image);
    const auto at = [&](int x, int y) {
        return sums[static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width + 1) +
                    static_cast<std::size_t>(x)];
    };
    double best_energy = -1.0;
    for (int y = 0; y + best.height <= image.height; y += kSearchStep)
        for (int x = 0; x + best.width <= image.width; x += kSearchStep) {
            const double energy =
                at(x + best.width, y + best.height) - at(x, y + best.height) - at(x + best.width, y) + at(x, y);
            if (energy > best_energy) {
                best_energy = energy;
                best.x = x;
                best.y = y;
            }
        }
    return best;
}

std::vector<std::string> upscale_crop_columns(const EvalOptions& options) {
    std::vector<std::string> columns{"native"};
    for (const char* name : {"bilinear", "bicubic", "lanczos3", "spline", "spline_plain"})
        if (std::any_of(options.upscalers.begin(), options.upscalers.end(),
                        [&](const UpscalerVariant& v) { return v.name == name; }))
            columns.push_back(name);
    return columns;
}

void write_upscale_crops(const EvalResults& results, const std::filesystem::path& path) {
    const engine::Image* native = find_tile(results.upscale_tiles, "native", 1);
    if (!native) return;
    const CropWindow window = detail_window(*native);
    const std::vector<std::string> columns = upscale_crop_columns(results.options);
    const std::vector<int> factors = upscale_crop_factors(results.options);
    const int tile_w = window.width * kCropMagnification, tile_h = window.height * kCropMagnification;
    const int row_h = kLabelHeight + tile_h + kGap;
    engine::Image sheet = black_image(kRowLabelWidth + static_cast<int>(columns.size()) * (tile_w + kGap),
                                      static_cast<int>(factors.size()) * row_h);
    for (std::size_t r = 0; r < factors.size(); ++r) {
        const int y0 = static_cast<int>(r) * row_h;
        draw_text(sheet, 4, y0 + kLabelHeight + tile_h / 2 - 4, std::to_string(factors[r]) + 'x');
        for (std::size_t c = 0; c < columns.size(); ++c) {
            const int factor = columns[c] == "native" ? 1 : factors[r];
            const int x0 = kRowLabelWidth + static_cast<int>(c) * (tile_w + kGap);
            draw_text(sheet, x0 + 2, y0 + 4, tile_label(results, columns[c], factor));
            const engine::Image* image = find_tile(results.upscale_tiles, columns[c], factor);
            if (image && image->width == native->width && image->height == native->height)
                draw_crop(sheet, *image, window, x0, y0 + kLabelHeight);
        }
    }
    engine::write_png(path, sheet);
}

}  // namespace splat_lod::eval
