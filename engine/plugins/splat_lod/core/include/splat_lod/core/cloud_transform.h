#pragma once
// A rigid change of frame applied to a cloud's stored values: positions p' = R·p + t, rotations
// q' = q_R·q, log-scales, opacities and the SH DC unchanged, and the higher SH bands rotated so that
// every Gaussian's colour seen along R·d is what it was along d (exact for any rotation, band by band).
// The world import turns a capture into the world's Y-up frame with it.
#include <array>

#include <glm/glm.hpp>

#include "splat_lod/core/splat_cloud.h"

namespace splat_lod {

// The band-l block (l = 1..3) of the SH rotation for R: coefficients k = l², …, (l+1)² − 1 of a
// rotated Gaussian are rows · old coefficients. Solved once per rotation from the basis at fixed
// directions (least squares over more directions than unknowns; the fit is exact).
struct ShRotation {
    std::array<std::array<double, 49>, 3> bands{};  // band l at [l − 1], (2l+1)² row-major
};
ShRotation sh_rotation(const glm::dmat3& rotation);

// Throws engine::Error when `rotation` is not a rotation (orthonormal, determinant +1, within 1e−6).
void transform_cloud(SplatCloud& cloud, const glm::dmat3& rotation, const glm::dvec3& translation);

// The rotation taking the unit vector `from` onto `to` about their common normal (the identity when
// they agree, a half turn about an axis normal to both when they are opposite).
glm::dmat3 rotation_between(const glm::dvec3& from, const glm::dvec3& to);

}  // namespace splat_lod
