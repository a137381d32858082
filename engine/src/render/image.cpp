#include "engine/render/image.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include <stb_image.h>
#include <stb_image_write.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"

namespace engine {

Image read_png(const std::filesystem::path& path) {
    const auto bytes = read_binary_file(path);
    int w = 0, h = 0, n = 0;
    stbi_uc* data = stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &n, 4);
    if (data == nullptr) fail(path.string() + ": cannot decode image: " + stbi_failure_reason());
    Image image{w, h,
                std::vector<std::uint8_t>(data, data + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4)};
    stbi_image_free(data);
    return image;
}

void write_png(const std::filesystem::path& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4)
        fail(path.string() + ": cannot write an empty or inconsistent image");
    std::vector<std::uint8_t> png;
    const auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<std::uint8_t>*>(context);
        const auto* bytes = static_cast<const std::uint8_t*>(data);
        out->insert(out->end(), bytes, bytes + size);
    };
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4))
        fail(path.string() + ": PNG encoding failed");
    write_file_atomic(path, png);
}

ImageDifference compare_images(const Image& a, const Image& b, int threshold) {
    if (a.width != b.width || a.height != b.height)
        fail("compare_images(): sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
             std::to_string(b.width) + "x" + std::to_string(b.height));
    ImageDifference d;
    d.visual = Image{a.width, a.height, std::vector<std::uint8_t>(a.rgba.size(), 255)};
    double squared = 0.0;
    std::size_t over = 0;
    const std::size_t pixels = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
    for (std::size_t p = 0; p < pixels; ++p) {
        int pixel_max = 0;
        for (int c = 0; c < 3; ++c) {
            const int diff = std::abs(int(a.rgba[p * 4 + static_cast<std::size_t>(c)]) -
                                      int(b.rgba[p * 4 + static_cast<std::size_t>(c)]));
            squared += double(diff) * double(diff);
            pixel_max = std::max(pixel_max, diff);
            d.visual.rgba[p * 4 + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(std::min(255, diff * 4));
        }
        d.max_channel_difference = std::max(d.max_channel_difference, pixel_max);
        if (pixel_max > threshold) ++over;
    }
    const double mse = squared / (double(pixels) * 3.0 * 255.0 * 255.0);
    d.psnr_db = mse > 0.0 ? -10.0 * std::log10(mse) : std::numeric_limits<double>::infinity();
    d.fraction_over_threshold = pixels ? double(over) / double(pixels) : 0.0;
    return d;
}

Image depth_image(const std::vector<float>& depth, int width, int height) {
    if (width < 0 || height < 0 || depth.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        fail("engine::depth_image: " + std::to_string(depth.size()) + " depths for " + std::to_string(width) + "x" +
             std::to_string(height) + " pixels");
    float nearest = std::numeric_limits<float>::infinity(), farthest = 0.0f;
    for (const float d : depth)
        if (std::isfinite(d) && d > 0.0f) {
            nearest = std::min(nearest, d);
            farthest = std::max(farthest, d);
        }
    Image image{width, height, std::vector<std::uint8_t>(depth.size() * 4, 0)};
    const double lo = 1.0 / farthest, hi = 1.0 / nearest;
    for (std::size_t p = 0; p < depth.size(); ++p) {
        image.rgba[4 * p + 3] = 255;
        if (!(std::isfinite(depth[p]) && depth[p] > 0.0f)) continue;
        const double t = hi > lo ? (1.0 / depth[p] - lo) / (hi - lo) : 1.0;
        const auto grey = static_cast<std::uint8_t>(std::lround(48.0 + 207.0 * t));
        image.rgba[4 * p] = image.rgba[4 * p + 1] = image.rgba[4 * p + 2] = grey;
    }
    return image;
}

Image side_by_side(const Image& left, const Image& right) {
    if (left.height != right.height)
        fail("side_by_side(): images of " + std::to_string(left.height) + " and " + std::to_string(right.height) +
             " rows");
    Image both{left.width + right.width, left.height, {}};
    both.rgba.reserve(static_cast<std::size_t>(both.width) * static_cast<std::size_t>(both.height) * 4);
    for (int y = 0; y < both.height; ++y)
        for (const Image* half : {&left, &right}) {
            const std::uint8_t* row = half->pixel(0, y);
            both.rgba.insert(both.rgba.end(), row, row + static_cast<std::size_t>(half->width) * 4);
        }
    return both;
}

}  // namespace engine
