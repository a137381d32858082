#pragma once
// A world-space bound on how far a Gaussian reaches for the purposes of pixel coverage
// (docs/algorithms.md §2), shared by whatever needs "could this Gaussian be large enough at distance z":
// the chunk manifest's per-level bounds (world_manifest.h) and the GPU cluster bounds of
// build_clusters() in runtime/src/gpu/gpu_scene.cpp (header-only and GL-free so that neither side needs
// another library).
//
// Coverage takes the shorter chord: S² ≤ 2·L·λ_min(Σ2D) ≤ 2·L·‖J‖₂²·σ_mid² (Courant–Fischer: the
// projected 2D covariance's smaller eigenvalue cannot exceed the 3D middle one), and
// S² ≤ L·‖J‖₂²·σ_max² always, with L = 2·ln(255·opacity). So with e = √L·min(σ_max, √2·σ_mid) the
// coverage at depth z with focal length f is at most 2·e·f / z.
#include <algorithm>
#include <cmath>

#include <glm/vec3.hpp>

namespace splat_lod::world {

// Numerically safe logistic function (no overflow for large |x|).
inline double opacity_from_logit(double logit) {
    return logit >= 0.0 ? 1.0 / (1.0 + std::exp(-logit)) : std::exp(logit) / (1.0 + std::exp(logit));
}

// e = sqrt(2·ln(255·o))·min(σ_max, √2·σ_mid); 0 when the opacity is at most 1/255 (never visible).
inline double gaussian_extent(const glm::vec3& log_scale, float opacity_logit) {
    const double opacity = opacity_from_logit(static_cast<double>(opacity_logit));
    if (!(opacity > 1.0 / 255.0)) return 0.0;
    glm::vec3 s = log_scale;
    std::sort(&s.x, &s.x + 3);
    const double sigma =
        std::min(std::exp(static_cast<double>(s.z)), std::sqrt(2.0) * std::exp(static_cast<double>(s.y)));
    return std::sqrt(2.0 * std::log(255.0 * opacity)) * sigma;
}

// How far from its mean a Gaussian's α = 1/255 ellipsoid reaches: sqrt(2·ln(255·o))·σ_max; 0 when
// the opacity is at most 1/255. Its projection stays within that distance's image (the frustum
// test of the GPU clusters, splat_clusters.comp.glsl).
inline double gaussian_reach(const glm::vec3& log_scale, float opacity_logit) {
    const double opacity = opacity_from_logit(static_cast<double>(opacity_logit));
    if (!(opacity > 1.0 / 255.0)) return 0.0;
    const double sigma = std::exp(static_cast<double>(std::max({log_scale.x, log_scale.y, log_scale.z})));
    return std::sqrt(2.0 * std::log(255.0 * opacity)) * sigma;
}

}  // namespace splat_lod::world
