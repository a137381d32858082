// Real spherical harmonics up to degree 3 with the constants and sign conventions of 3DGS
// (gaussian-splatting, utils/sh_utils.py and forward.cu computeColorFromSH), in double precision.
#include <algorithm>
#include <array>
#include <cmath>

#include "splat_lod/core/reference_renderer.h"

namespace splat_lod::reference {
namespace {

constexpr double kC0 = 0.28209479177387814;
constexpr double kC1 = 0.4886025119029199;
constexpr std::array<double, 5> kC2 = {1.0925484305920792, -1.0925484305920792, 0.31539156525252005,
                                       -1.0925484305920792, 0.5462742152960396};
constexpr std::array<double, 7> kC3 = {-0.5900435899266435, 2.890611442640554, -0.4570457994644658, 0.3731763325901154,
                                       -0.4570457994644658, 1.445305721320277, -0.5900435899266435};

}  // namespace

std::array<double, 16> sh_basis(const glm::dvec3& d, int degree) {
    std::array<double, 16> basis{};
    const double x = d.x, y = d.y, z = d.z;
    if (degree >= 1) {
        basis[1] = -kC1 * y;
        basis[2] = kC1 * z;
        basis[3] = -kC1 * x;
    }
    const double xx = x * x, yy = y * y, zz = z * z;
    if (degree >= 2) {
        basis[4] = kC2[0] * x * y;
        basis[5] = kC2[1] * y * z;
        basis[6] = kC2[2] * (2.0 * zz - xx - yy);
        basis[7] = kC2[3] * x * z;
        basis[8] = kC2[4] * (xx - yy);
    }
    if (degree >= 3) {
        basis[9] = kC3[0] * y * (3.0 * xx - yy);
        basis[10] = kC3[1] * x * y * z;
        basis[11] = kC3[2] * y * (4.0 * zz - xx - yy);
        basis[12] = kC3[3] * z * (2.0 * zz - 3.0 * xx - 3.0 * yy);
        basis[13] = kC3[4] * x * (4.0 * zz - xx - yy);
        basis[14] = kC3[5] * z * (xx - yy);
        basis[15] = kC3[6] * x * (xx - 3.0 * yy);
    }
    return basis;
}

glm::dvec3 sh_colour(const SplatCloud& cloud, std::size_t index, int degree, const glm::dvec3& direction) {
    return glm::max(sh_colour_unclamped(cloud, index, degree, direction), glm::dvec3(0.0));
}

glm::dvec3 sh_colour_unclamped(const SplatCloud& cloud, std::size_t index, int degree, const glm::dvec3& direction) {
    degree = std::clamp(std::min(degree, cloud.sh_degree), 0, kMaxShDegree);
    glm::dvec3 result = kC0 * glm::dvec3(cloud.sh_dc[index]);
    const double length = glm::length(direction);
    // A zero direction has no view dependence to evaluate: the DC term alone is the colour.
    if (degree > 0 && length > 0.0 && std::isfinite(length)) {
        const auto basis = sh_basis(direction / length, degree);
        const float* rest = cloud.sh_rest.data() + index * cloud.sh_rest_stride();
        for (int k = 1; k <= sh_rest_coeffs(degree); ++k) {
            const float* coefficient = rest + 3 * (k - 1);  // coefficient-major, channel-minor
            result += basis[static_cast<std::size_t>(k)] * glm::dvec3(coefficient[0], coefficient[1], coefficient[2]);
        }
    }
    return result + 0.5;
}

}  // namespace splat_lod::reference
