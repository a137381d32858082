// Rigid frame changes of a cloud, with the SH bands rotated (cloud_transform.h).
#include "splat_lod/core/cloud_transform.h"

#include <cmath>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "splat_lod/core/reference_renderer.h"

namespace splat_lod {
namespace {

constexpr int kDirections = 32;

// Fixed, well-spread unit directions (a Fibonacci sphere).
glm::dvec3 direction(int i) {
    const double golden = 2.399963229728653;  // π·(3 − √5)
    const double z = 1.0 - 2.0 * (static_cast<double>(i) + 0.5) / kDirections;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {r * std::cos(golden * i), r * std::sin(golden * i), z};
}

// Solves the n × n system a·x = b for the n columns of b in place (Gaussian elimination with partial
// pivoting; a is the well-conditioned normal matrix of a basis on spread directions).
void solve(std::vector<double>& a, std::vector<double>& b, int n) {
    const auto at = [n](std::vector<double>& m, int r, int c) -> double& {
        return m[static_cast<std::size_t>(r * n + c)];
    };
    for (int col = 0; col < n; ++col) {
        int pivot = col;
        for (int r = col + 1; r < n; ++r)
            if (std::fabs(at(a, r, col)) > std::fabs(at(a, pivot, col))) pivot = r;
        for (int c = 0; c < n; ++c) {
            std::swap(at(a, col, c), at(a, pivot, c));
            std::swap(at(b, col, c), at(b, pivot, c));
        }
        for (int r = 0; r < n; ++r) {
            if (r == col) continue;
            const double f = at(a, r, col) / at(a, col, col);
            for (int c = 0; c < n; ++c) {
                at(a, r, c) -= f * at(a, col, c);
                at(b, r, c) -= f * at(b, col, c);
            }
        }
    }
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) at(b, r, c) /= at(a, r, r);
}

// Band l: with A[d][j] = Y_j(d) and B[d][i] = Y_i(Rᵀ·d), the rotated coefficients c' satisfy A·c' = B·c
// for every direction, so M = (AᵀA)⁻¹·AᵀB.
std::array<double, 49> band_rotation(const glm::dmat3& rotation, int l) {
    const int n = 2 * l + 1, first = l * l;
    std::vector<double> ata(static_cast<std::size_t>(n * n), 0.0), atb(static_cast<std::size_t>(n * n), 0.0);
    for (int d = 0; d < kDirections; ++d) {
        const auto a = reference::sh_basis(direction(d), l);
        const auto b = reference::sh_basis(glm::transpose(rotation) * direction(d), l);
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) {
                ata[static_cast<std::size_t>(r * n + c)] +=
                    a[static_cast<std::size_t>(first + r)] * a[static_cast<std::size_t>(first + c)];
                atb[static_cast<std::size_t>(r * n + c)] +=
                    a[static_cast<std::size_t>(first + r)] * b[static_cast<std::size_t>(first + c)];
            }
    }
    solve(ata, atb, n);
    std::array<double, 49> out{};
    std::copy(atb.begin(), atb.end(), out.begin());
    return out;
}

Rotation quaternion_of(const glm::dmat3& m) {
    // Shepperd's method: the largest of the four squared components first, for stability.
    const double trace = m[0][0] + m[1][1] + m[2][2];
    glm::dvec4 q;  // w, x, y, z; m[c][r] is column c, row r
    if (trace > 0.0) {
        const double s = 2.0 * std::sqrt(1.0 + trace);
        q = {0.25 * s, (m[1][2] - m[2][1]) / s, (m[2][0] - m[0][2]) / s, (m[0][1] - m[1][0]) / s};
    } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
        const double s = 2.0 * std::sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]);
        q = {(m[1][2] - m[2][1]) / s, 0.25 * s, (m[1][0] + m[0][1]) / s, (m[2][0] + m[0][2]) / s};
    } else if (m[1][1] > m[2][2]) {
        const double s = 2.0 * std::sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]);
        q = {(m[2][0] - m[0][2]) / s, (m[1][0] + m[0][1]) / s, 0.25 * s, (m[2][1] + m[1][2]) / s};
    } else {
        const double s = 2.0 * std::sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]);
        q = {(m[0][1] - m[1][0]) / s, (m[2][0] + m[0][2]) / s, (m[2][1] + m[1][2]) / s, 0.25 * s};
    }
    q /= glm::length(q);
    return {static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z), static_cast<float>(q.w)};
}

Rotation multiply(const Rotation& a, const Rotation& b) {
    return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

void check_rotation(const glm::dmat3& r) {
    const glm::dmat3 identity = glm::transpose(r) * r;
    double worst = std::fabs(glm::determinant(r) - 1.0);
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::fabs(identity[c][k] - (c == k ? 1.0 : 0.0)));
    if (!(worst <= 1e-6))
        engine::fail("splat_lod::transform_cloud(): not a rotation (off by " + std::to_string(worst) + ")");
}

void rotate_sh(SplatCloud& cloud, const ShRotation& sh) {
    for (std::size_t i = 0; i < cloud.size(); ++i)
        for (int l = 1; l <= cloud.sh_degree; ++l) {
            const int n = 2 * l + 1, first = l * l;
            const auto& m = sh.bands[static_cast<std::size_t>(l - 1)];
            for (int channel = 0; channel < 3; ++channel) {
                double old[7];
                for (int c = 0; c < n; ++c) old[c] = cloud.sh_rest_at(i, first + c, channel);
                for (int r = 0; r < n; ++r) {
                    double sum = 0.0;
                    for (int c = 0; c < n; ++c) sum += m[static_cast<std::size_t>(r * n + c)] * old[c];
                    cloud.sh_rest_at(i, first + r, channel) = static_cast<float>(sum);
                }
            }
        }
}

}  // namespace

ShRotation sh_rotation(const glm::dmat3& rotation) {
    ShRotation out;
    for (int l = 1; l <= kMaxShDegree; ++l) out.bands[static_cast<std::size_t>(l - 1)] = band_rotation(rotation, l);
    return out;
}

void transform_cloud(SplatCloud& cloud, const glm::dmat3& rotation, const glm::dvec3& translation) {
    cloud.check_consistent();
    check_rotation(rotation);
    const Rotation turn = quaternion_of(rotation);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        cloud.positions[i] = glm::vec3(rotation * glm::dvec3(cloud.positions[i]) + translation);
        cloud.rotations[i] = multiply(turn, cloud.rotations[i]);
    }
    if (cloud.sh_degree > 0) rotate_sh(cloud, sh_rotation(rotation));
}

glm::dmat3 rotation_between(const glm::dvec3& from, const glm::dvec3& to) {
    const glm::dvec3 a = glm::normalize(from), b = glm::normalize(to);
    const glm::dvec3 axis = glm::cross(a, b);
    const double c = glm::dot(a, b), s = glm::length(axis);
    if (s < 1e-12) {
        if (c > 0.0) return glm::dmat3(1.0);
        // Opposite: a half turn about any axis normal to a (x when a is not along x).
        const glm::dvec3 normal = std::fabs(a.x) < 0.9 ? glm::normalize(glm::cross(a, glm::dvec3(1, 0, 0)))
                                                       : glm::normalize(glm::cross(a, glm::dvec3(0, 1, 0)));
        return 2.0 * glm::outerProduct(normal, normal) - glm::dmat3(1.0);
    }
    const glm::dvec3 k = axis / s;
    const glm::dmat3 cross_k(0.0, k.z, -k.y, -k.z, 0.0, k.x, k.y, -k.x, 0.0);  // columns: [k]× with [k]×v = k × v
    return glm::dmat3(1.0) + s * cross_k + (1.0 - c) * cross_k * cross_k;
}

}  // namespace splat_lod
