// Node transforms applied to Gaussians (positions and covariances), and the merge of primitives.
#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "engine/core/error.h"
#include "gltf_splats.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/splat_math.h"

namespace splat_lod::io {
namespace {

Rotation to_rotation(const glm::dquat& q) {
    return {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)};
}

// Gaussian i under a general linear map: Σ' = A·R·S²·Rᵀ·Aᵀ, decomposed again.
void transform_covariance(SplatCloud& cloud, std::size_t i, const glm::dmat3& a) {
    const Rotation& q = cloud.rotations[i];  // not normalised yet (sanitise does that at the end)
    const glm::dquat unit = glm::normalize(glm::dquat(q.w, q.x, q.y, q.z));
    const glm::dmat3 r = glm::mat3_cast(unit);
    const glm::dvec3 s = glm::exp(glm::dvec3(cloud.log_scales[i]));
    const glm::dmat3 m = a * r * glm::dmat3(glm::dvec3(s.x, 0, 0), glm::dvec3(0, s.y, 0), glm::dvec3(0, 0, s.z));
    glm::dvec3 values;
    glm::dmat3 v;
    math::symmetric_eigen(m * glm::transpose(m), values, v);
    if (glm::determinant(v) < 0.0) v[2] = -v[2];
    cloud.rotations[i] = to_rotation(glm::quat_cast(v));
    for (int c = 0; c < 3; ++c) cloud.log_scales[i][c] = static_cast<float>(0.5 * std::log(std::max(values[c], 0.0)));
}

}  // namespace

void apply_node_transform(SplatCloud& cloud, const glm::dmat4& world, const std::string& name, const std::string& label,
                          LoadReport& report) {
    if (world == glm::dmat4(1.0)) return;
    const glm::dmat3 a(world);
    const glm::dvec3 t(world[3]);
    const glm::dvec3 lengths(glm::length(a[0]), glm::length(a[1]), glm::length(a[2]));
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(lengths[c]) || !(lengths[c] > 1e-12) || !std::isfinite(t[c]))
            engine::fail(name + ": " + label + ": the transform is not decomposable (zero or non-finite scale)");
    const glm::dmat3 unit(a[0] / lengths.x, a[1] / lengths.y, a[2] / lengths.z);
    const double det = glm::determinant(unit);
    if (std::abs(det) < 1.0 - 1e-4)
        engine::fail(name + ": " + label + ": the transform is not decomposable (it shears)");
    const bool rotates = glm::length(glm::dvec3(unit[0] - glm::dvec3(1, 0, 0))) > 1e-9 ||
                         glm::length(glm::dvec3(unit[1] - glm::dvec3(0, 1, 0))) > 1e-9 || det < 0.0;
    if (det < 0.0) report.warnings.push_back(label + ": the transform mirrors (negative scale)");
    if (rotates && cloud.sh_degree >= 1)
        report.warnings.push_back(label + ": the transform rotates; SH coefficients of degree 1 to " +
                                  std::to_string(cloud.sh_degree) + " are not rotated with it");
    const double mean = (lengths.x + lengths.y + lengths.z) / 3.0;
    const bool uniform = det > 0.0 && glm::length(lengths - glm::dvec3(mean)) <= 1e-7 * mean;
    const glm::dquat turn = glm::quat_cast(unit);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        cloud.positions[i] = glm::vec3(a * glm::dvec3(cloud.positions[i]) + t);
        if (uniform) {
            const Rotation& r = cloud.rotations[i];
            cloud.rotations[i] = to_rotation(turn * glm::normalize(glm::dquat(r.w, r.x, r.y, r.z)));
            cloud.log_scales[i] = glm::vec3(glm::dvec3(cloud.log_scales[i]) + std::log(mean));
        } else {
            transform_covariance(cloud, i, a);
        }
    }
}

void append_cloud(SplatCloud& cloud, const SplatCloud& part) {
    if (part.sh_degree > cloud.sh_degree) cloud.set_sh_degree(part.sh_degree);
    const std::size_t base = cloud.size();
    // Primitives of one kind keep it; a mix hands over in no one way.
    if (base == 0)
        cloud.level_handover = part.level_handover;
    else if (cloud.level_handover != part.level_handover)
        cloud.level_handover = LevelHandover::unknown;
    cloud.resize(base + part.size());
    std::copy(part.positions.begin(), part.positions.end(),
              cloud.positions.begin() + static_cast<std::ptrdiff_t>(base));
    std::copy(part.rotations.begin(), part.rotations.end(),
              cloud.rotations.begin() + static_cast<std::ptrdiff_t>(base));
    std::copy(part.log_scales.begin(), part.log_scales.end(),
              cloud.log_scales.begin() + static_cast<std::ptrdiff_t>(base));
    std::copy(part.opacity_logits.begin(), part.opacity_logits.end(),
              cloud.opacity_logits.begin() + static_cast<std::ptrdiff_t>(base));
    std::copy(part.sh_dc.begin(), part.sh_dc.end(), cloud.sh_dc.begin() + static_cast<std::ptrdiff_t>(base));
    std::copy(part.lod_level.begin(), part.lod_level.end(),
              cloud.lod_level.begin() + static_cast<std::ptrdiff_t>(base));
    std::copy(part.coverage_min.begin(), part.coverage_min.end(),
              cloud.coverage_min.begin() + static_cast<std::ptrdiff_t>(base));
    std::copy(part.coverage_max.begin(), part.coverage_max.end(),
              cloud.coverage_max.begin() + static_cast<std::ptrdiff_t>(base));
    const int coeffs = sh_rest_coeffs(part.sh_degree);
    for (std::size_t i = 0; i < part.size(); ++i)
        for (int k = 1; k <= coeffs; ++k)
            for (int c = 0; c < 3; ++c) cloud.sh_rest_at(base + i, k, c) = part.sh_rest_at(i, k, c);
    for (const auto& extra : part.extras) {
        ExtraProperty* into = cloud.find_extra(extra.name);
        if (!into) into = &cloud.add_extra(extra.name);
        std::copy(extra.values.begin(), extra.values.end(), into->values.begin() + static_cast<std::ptrdiff_t>(base));
    }
}

}  // namespace splat_lod::io
