#pragma once
// 8-bit RGBA images on the CPU with PNG I/O (stb_image / stb_image_write) and comparison.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace engine {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  // row-major, top row first

    std::uint8_t* pixel(int x, int y) {
        return &rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4];
    }
    const std::uint8_t* pixel(int x, int y) const {
        return &rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4];
    }
};

// `left` and `right` next to each other (a stereo pair); throws engine::Error unless their heights agree.
Image side_by_side(const Image& left, const Image& right);

Image read_png(const std::filesystem::path& path);                      // throws naming the file
void write_png(const std::filesystem::path& path, const Image& image);  // atomic replace

struct ImageDifference {
    double psnr_db = 0.0;  // over RGB, values in [0, 1]; +inf for identical images
    int max_channel_difference = 0;
    double fraction_over_threshold = 0.0;  // pixels whose RGB difference exceeds the threshold
    Image visual;                          // |a − b| × 4, for looking at
};

// Compares RGB of two images of the same size (throws if sizes differ).
ImageDifference compare_images(const Image& a, const Image& b, int threshold = 8);

// A view depth image (z = −z_view per pixel, rows top first, +inf where nothing is) for looking at:
// grey by inverse depth between the nearest and the farthest finite depth (white the nearest, dark grey
// the farthest), black where nothing is. Throws when `depth` does not hold width × height values.
Image depth_image(const std::vector<float>& depth, int width, int height);

}  // namespace engine
