#pragma once
// Small CPU maths on Gaussians shared by the bake and the world generator's chunk groups.
#include <cstdint>

#include <glm/glm.hpp>

#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::math {

// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations: the columns of
// `vectors` are orthonormal eigenvectors, `values` the eigenvalues.
void symmetric_eigen(glm::dmat3 a, glm::dvec3& values, glm::dmat3& vectors);
// The rotation matrix of a unit quaternion (w, x, y, z).
glm::dmat3 rotation_of(const Rotation& q);
// Spreads the low 21 bits of v to every third bit (one axis of a 63-bit Morton code).
std::uint64_t spread_bits(std::uint64_t v);

}  // namespace splat_lod::math
