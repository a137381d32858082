#pragma once
// Image error metrics of the evaluation (docs/algorithms.md §6), on float RGB in [0, 1]:
// PSNR over all pixels and channels; SSIM with an 11×11 Gaussian window (σ = 1.5) per channel,
// averaged; and the k×k area average that turns a full-resolution render into the reference.
#include <string>
#include <vector>

#include "engine/render/image.h"

namespace splat_lod::eval {

// RGB, row-major, top row first, 3 floats per pixel.
struct FloatImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;

    float& at(int x, int y, int c) {
        return rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3 +
                   static_cast<std::size_t>(c)];
    }
    float at(int x, int y, int c) const {
        return rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3 +
                   static_cast<std::size_t>(c)];
    }
};

FloatImage make_float_image(int width, int height, float value = 0.0f);
FloatImage to_float(const engine::Image& image);  // drops alpha, divides by 255
engine::Image to_rgba8(const FloatImage& image);  // rounds, alpha 255

// +inf for identical images. Throws engine::Error when the sizes differ.
double psnr(const FloatImage& a, const FloatImage& b);
// Mean SSIM (Wang et al. 2004, C1 = 0.01², C2 = 0.03²) over the pixels whose whole 11×11 window
// lies inside the image ("valid" windows, as skimage and the 3DGS papers compute it); images
// smaller than the window use one window clipped to the image. Throws when the sizes differ.
double ssim(const FloatImage& a, const FloatImage& b);

// Throws engine::Error naming `what` when k is not a usable scale for a width × height image:
// k < 1, k larger than a side, or a side not divisible by k.
void check_scale(int k, int width, int height, const std::string& what);
// Each output pixel is the mean of a k×k block (box filter), the reference at scale k.
FloatImage area_average(const FloatImage& image, int k);

}  // namespace splat_lod::eval
