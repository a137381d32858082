#pragma once
// Shared by the reference-renderer tests: small scenes built in code and the expected values of
// docs/algorithms.md §1 written out independently of the renderer.
#include <algorithm>
#include <cmath>
#include <span>

#include <gtest/gtest.h>

#include "splat_lod/core/reference_renderer.h"

namespace splat_lod::reference::test {

inline constexpr double kC0 = 0.28209479177387814;
inline constexpr double kC1 = 0.4886025119029199;

inline float logit(double opacity) {
    return static_cast<float>(std::log(opacity / (1.0 - opacity)));
}
inline double sigmoid(float logit_value) {
    return 1.0 / (1.0 + std::exp(-static_cast<double>(logit_value)));
}

// DC coefficients whose degree-0 colour is `colour` (0.5 + C0·dc = colour).
inline glm::vec3 dc_for(const glm::dvec3& colour) {
    return glm::vec3((colour - 0.5) / kC0);
}
inline glm::dvec3 dc_colour(const glm::vec3& dc) {
    return glm::max(0.5 + kC0 * glm::dvec3(dc), glm::dvec3(0.0));
}

// Appends an isotropic Gaussian with identity rotation.
inline std::size_t add_gaussian(SplatCloud& cloud, const glm::vec3& position, float log_scale, double opacity,
                                const glm::dvec3& colour) {
    const std::size_t i = cloud.size();
    cloud.resize(i + 1);
    cloud.positions[i] = position;
    cloud.log_scales[i] = glm::vec3(log_scale);
    cloud.opacity_logits[i] = logit(opacity);
    cloud.sh_dc[i] = dc_for(colour);
    return i;
}

// A camera at the origin looking down −Z with +Y up (identity view), focal length f, the
// principal point at the image centre.
inline ReferenceCamera axis_camera(int width, int height, double focal = 100.0) {
    ReferenceCamera camera;
    camera.width = width;
    camera.height = height;
    camera.fx = camera.fy = focal;
    camera.cx = 0.5 * width;
    camera.cy = 0.5 * height;
    return camera;
}

// §1's α of a projected Gaussian at the centre of pixel (x, y).
inline double alpha_at_pixel(const ProjectedGaussian& g, int x, int y) {
    const glm::dvec2 d = glm::dvec2(x + 0.5, y + 0.5) - g.mean;
    const double q = g.conic.x * d.x * d.x + 2.0 * g.conic.y * d.x * d.y + g.conic.z * d.y * d.y;
    return std::min(kMaxAlpha, g.opacity * std::exp(-0.5 * q));
}

inline ReferenceImage render_cloud(const SplatCloud& cloud, const ReferenceCamera& camera,
                                   const ReferenceSettings& settings = {}, ReferenceStats* stats = nullptr,
                                   const glm::dmat4& model = glm::dmat4(1.0)) {
    const ReferenceInstance instance{&cloud, model};
    return render_reference(std::span(&instance, 1), camera, settings, nullptr, stats);
}

inline ::testing::AssertionResult all_finite(const ReferenceImage& image) {
    for (std::size_t i = 0; i < image.rgb.size(); ++i)
        if (!std::isfinite(image.rgb[i]))
            return ::testing::AssertionFailure() << "rgb value " << i << " is " << image.rgb[i];
    for (std::size_t i = 0; i < image.alpha.size(); ++i)
        if (!(image.alpha[i] >= 0.0 && image.alpha[i] <= 1.0))
            return ::testing::AssertionFailure() << "alpha " << i << " is " << image.alpha[i];
    return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult stats_add_up(const ReferenceStats& s) {
    const std::size_t sum = s.non_finite_dropped + s.zero_rotation_dropped + s.culled_near + s.culled_invisible +
                            s.culled_degenerate + s.culled_outside + s.drawn;
    if (sum == s.considered) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "stats sum " << sum << " != considered " << s.considered;
}

// True when every pixel is exactly the background with nothing blended.
inline ::testing::AssertionResult is_background(const ReferenceImage& image, const glm::dvec3& background) {
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (image.colour_at(x, y) != background || image.alpha_at(x, y) != 0.0 || image.contributors_at(x, y) != 0)
                return ::testing::AssertionFailure() << "pixel (" << x << ", " << y << ") is not the background";
    return ::testing::AssertionSuccess();
}

}  // namespace splat_lod::reference::test
