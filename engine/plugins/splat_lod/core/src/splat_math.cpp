// CPU maths on Gaussians (splat_lod/core/splat_math.h).
#include "splat_lod/core/splat_math.h"

#include <cmath>

namespace splat_lod::math {

void symmetric_eigen(glm::dmat3 a, glm::dvec3& values, glm::dmat3& vectors) {
    vectors = glm::dmat3(1.0);
    for (int sweep = 0; sweep < 32; ++sweep) {
        const double off = a[1][0] * a[1][0] + a[2][0] * a[2][0] + a[2][1] * a[2][1];
        const double diagonal = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (!(off > 1e-30 * diagonal)) break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (a[q][p] == 0.0) continue;
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[q][p]);
                const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                glm::dmat3 r(1.0);
                r[p][p] = c;
                r[q][q] = c;
                r[q][p] = s;
                r[p][q] = -s;
                a = glm::transpose(r) * a * r;
                vectors = vectors * r;
            }
    }
    values = {a[0][0], a[1][1], a[2][2]};
}

glm::dmat3 rotation_of(const Rotation& q) {
    const double w = q.w, x = q.x, y = q.y, z = q.z;
    return glm::dmat3(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y), 2.0 * (x * y - w * z),
                      1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + w * x), 2.0 * (x * z + w * y), 2.0 * (y * z - w * x),
                      1.0 - 2.0 * (x * x + y * y));
}

std::uint64_t spread_bits(std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
}

}  // namespace splat_lod::math
