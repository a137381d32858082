// The per-Gaussian step of the reference renderer (docs/algorithms.md §1): activation, culling, the EWA
// projection of the covariance (3DGS, Kerbl et al. 2023, Eq. 5, after Zwicker et al. 2001), the
// low-pass dilation, the α ≥ 1/255 extent and the SH colour, all in double precision.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "engine/core/error.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/upscale.h"

namespace splat_lod::reference {
namespace detail {
namespace {

// Same threshold as sanitise(): below it a quaternion carries no usable direction.
constexpr double kMinQuaternionNormSquared = 1e-20;

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::dvec2& v) {
    return std::isfinite(v.x) && std::isfinite(v.y);
}
bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

template <typename Matrix>
bool finite_matrix(const Matrix& m) {
    for (glm::length_t c = 0; c < m.length(); ++c)
        for (glm::length_t r = 0; r < m[c].length(); ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// Every attribute the renderer reads, SH coefficients of the stored degree included (§7: NaN/Inf
// anywhere means the Gaussian is dropped, even in a coefficient the degree cap would skip).
bool finite_attributes(const SplatCloud& cloud, std::size_t i) {
    const Rotation& q = cloud.rotations[i];
    if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return false;
    if (!finite(cloud.positions[i]) || !finite(cloud.log_scales[i]) || !finite(cloud.sh_dc[i])) return false;
    if (!std::isfinite(cloud.opacity_logits[i])) return false;
    const std::size_t stride = cloud.sh_rest_stride();
    const float* rest = cloud.sh_rest.data() + i * stride;
    return std::all_of(rest, rest + stride, [](float v) { return std::isfinite(v); });
}

// Normalised (w, x, y, z) → rotation matrix R of Σ = R S Sᵀ Rᵀ (3DGS Eq. 6), or nothing for a
// zero quaternion.
std::optional<glm::dmat3> rotation_matrix(const Rotation& r) {
    const double norm2 = double(r.w) * r.w + double(r.x) * r.x + double(r.y) * r.y + double(r.z) * r.z;
    if (!(norm2 >= kMinQuaternionNormSquared)) return std::nullopt;
    const double n = std::sqrt(norm2);
    const double w = r.w / n, x = r.x / n, y = r.y / n, z = r.z / n;
    return glm::dmat3(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y),   // column 0
                      2.0 * (x * y - w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + w * x),   // column 1
                      2.0 * (x * z + w * y), 2.0 * (y * z - w * x), 1.0 - 2.0 * (x * x + y * y));  // column 2
}

// Undilated Σ2D = A Aᵀ with A = J · (local_to_camera · R) · S (2×3), which equals J W₃ Σ W₃ᵀ Jᵀ for
// Σ = M R S Sᵀ Rᵀ Mᵀ. Its determinant is taken as the sum of the squared 2×2 minors of A
// (Cauchy–Binet): never negative, and free of the cancellation of xx·yy − xy² for 1e6:1 needles.
struct ScreenCovariance {
    double xx = 0.0, xy = 0.0, yy = 0.0, det = 0.0;
};

ScreenCovariance screen_covariance(const glm::dmat3& local_to_camera_rotation, const glm::dvec3& scale,
                                   const glm::dvec3& t, const ReferenceCamera& camera) {
    // Jacobian at the mean with x/z, y/z clamped as 3DGS does (forward.cu computeCov2D).
    const double limit_x = kJacobianClampFactor * camera.jacobian_clamp_tan_x();
    const double limit_y = kJacobianClampFactor * camera.jacobian_clamp_tan_y();
    const double tx = std::clamp(t.x / t.z, -limit_x, limit_x) * t.z;
    const double ty = std::clamp(t.y / t.z, -limit_y, limit_y) * t.z;
    const glm::dvec3 j0(camera.fx / t.z, 0.0, -camera.fx * tx / (t.z * t.z));
    const glm::dvec3 j1(0.0, camera.fy / t.z, -camera.fy * ty / (t.z * t.z));
    double a0[3], a1[3];
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 column = local_to_camera_rotation[k] * scale[k];
        a0[k] = glm::dot(j0, column);
        a1[k] = glm::dot(j1, column);
    }
    ScreenCovariance cov;
    for (int k = 0; k < 3; ++k) {
        cov.xx += a0[k] * a0[k];
        cov.xy += a0[k] * a1[k];
        cov.yy += a1[k] * a1[k];
        const int l = (k + 1) % 3;
        const double minor = a0[k] * a1[l] - a0[l] * a1[k];
        cov.det += minor * minor;
    }
    return cov;
}

ProjectedGaussian culled(ProjectedGaussian g, CullReason reason) {
    g.cull = reason;
    return g;
}

// Σ2D + dilation·I, the optional mip factor, and the conic. False when culled.
bool dilate(ProjectedGaussian& g, const ScreenCovariance& cov, const ReferenceSettings& settings) {
    const double d = settings.dilation;
    const double xx = cov.xx + d, yy = cov.yy + d;
    const double det = cov.det + d * (cov.xx + cov.yy) + d * d;  // det(Σ2D + d·I), exactly
    g.cov2d = {xx, cov.xy, yy};
    g.conic = {yy / det, -cov.xy / det, xx / det};
    if (!(det > 0.0) || !finite(g.conic)) {
        g.cull = CullReason::degenerate;
        return false;
    }
    if (settings.mip_filter) g.opacity *= std::sqrt(cov.det / det);
    if (g.opacity <= kMinAlpha) g.cull = CullReason::invisible;
    return g.drawn();
}

// Bounding box of dᵀ Σ2D⁻¹ d ≤ 2·ln(255·o) and the pixel centres (i + 0.5) inside it.
bool set_extent(ProjectedGaussian& g, const ReferenceCamera& camera) {
    const double r2 = 2.0 * std::log(255.0 * g.opacity);
    g.extent = {std::sqrt(r2 * g.cov2d.x), std::sqrt(r2 * g.cov2d.z)};
    const double x0 = std::max(std::ceil(g.mean.x - g.extent.x - 0.5), 0.0);
    const double x1 = std::min(std::floor(g.mean.x + g.extent.x - 0.5), camera.width - 1.0);
    const double y0 = std::max(std::ceil(g.mean.y - g.extent.y - 0.5), 0.0);
    const double y1 = std::min(std::floor(g.mean.y + g.extent.y - 0.5), camera.height - 1.0);
    if (!(x0 <= x1 && y0 <= y1)) return false;
    g.pixels = {static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(x1), static_cast<int>(y1)};
    return true;
}

}  // namespace

// Written in the two branches so that neither exp() overflows (logit ±60 and beyond).
double sigmoid(double logit) {
    if (logit >= 0.0) return 1.0 / (1.0 + std::exp(-logit));
    const double e = std::exp(logit);
    return e / (1.0 + e);
}

void check_camera(const ReferenceCamera& camera, const char* caller) {
    const auto bad = [&](const std::string& what) { engine::fail(std::string(caller) + ": " + what); };
    if (camera.width <= 0 || camera.height <= 0)
        bad("image size must be positive, got " + std::to_string(camera.width) + "x" + std::to_string(camera.height));
    if (!(camera.fx > 0.0 && camera.fy > 0.0 && std::isfinite(camera.fx) && std::isfinite(camera.fy)))
        bad("focal lengths must be positive and finite");
    if (!std::isfinite(camera.cx) || !std::isfinite(camera.cy) || !finite(camera.position) ||
        !finite_matrix(camera.view))
        bad("camera has a non-finite principal point, centre or view matrix");
    if (!(camera.clamp_tan_x >= 0.0 && camera.clamp_tan_y >= 0.0 && std::isfinite(camera.clamp_tan_x) &&
          std::isfinite(camera.clamp_tan_y)))
        bad("clamp_tan_x and clamp_tan_y must be finite and not negative (0: use the field of view)");
}

void check_settings(const ReferenceSettings& settings, const char* caller) {
    if (!(settings.dilation >= 0.0 && std::isfinite(settings.dilation)) || !std::isfinite(settings.znear))
        engine::fail(std::string(caller) + ": the dilation must be finite and not negative, znear finite");
}

InstanceFrame make_instance_frame(const SplatCloud& cloud, const glm::dmat4& model, const ReferenceCamera& camera,
                                  const ReferenceSettings& settings, int sh_degree_cap) {
    InstanceFrame frame;
    frame.sh_degree = std::clamp(std::min({cloud.sh_degree, sh_degree_cap, settings.sh_degree_cap}), 0, kMaxShDegree);
    const glm::dmat3 linear(model);
    if (!finite_matrix(model))
        frame.cull = CullReason::non_finite;
    else if (!(std::abs(glm::determinant(linear)) > 0.0))
        frame.cull = CullReason::degenerate;
    if (frame.cull != CullReason::none) return frame;
    frame.model_view = camera.view * model;
    // View (x right, y up, looking down −z) → image-aligned (x right, y down, z forward): a
    // rotation by 180° about x, so the projection below is 3DGS's with y measured downwards.
    const glm::dmat3 view_to_image_aligned(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);
    frame.local_to_camera = view_to_image_aligned * glm::dmat3(camera.view) * linear;
    // SH are a function of direction in the cloud's own frame. The direction used is from the
    // camera centre to the mean with both expressed in that frame, i.e. M⁻¹(μ_world − c): R⁻¹·d
    // for a rotation with uniform scale; under non-uniform scale or shear, the local direction that
    // the model maps onto the viewing ray (renormalised).
    frame.camera_local = glm::dvec3(glm::inverse(model) * glm::dvec4(camera.position, 1.0));
    if (!finite(frame.camera_local) || !finite_matrix(frame.local_to_camera)) frame.cull = CullReason::non_finite;
    return frame;
}

ProjectedGaussian project_in_frame(const SplatCloud& cloud, std::size_t index, const InstanceFrame& frame,
                                   const ReferenceCamera& camera, const ReferenceSettings& settings) {
    ProjectedGaussian g;
    if (frame.cull != CullReason::none) return culled(g, frame.cull);
    if (!finite_attributes(cloud, index)) return culled(g, CullReason::non_finite);
    const auto rotation = rotation_matrix(cloud.rotations[index]);
    if (!rotation) return culled(g, CullReason::zero_rotation);
    g.opacity = sigmoid(cloud.opacity_logits[index]);
    if (g.opacity <= kMinAlpha) return culled(g, CullReason::invisible);

    const glm::dvec3 local(cloud.positions[index]);
    const glm::dvec4 view = frame.model_view * glm::dvec4(local, 1.0);
    const glm::dvec3 t(view.x, -view.y, -view.z);  // image-aligned camera frame, t.z = −z_view
    if (!finite(t)) return culled(g, CullReason::non_finite);
    g.depth = t.z;
    if (!(t.z > settings.znear)) return culled(g, CullReason::near_plane);
    g.mean = {camera.cx + camera.fx * t.x / t.z, camera.cy + camera.fy * t.y / t.z};

    const glm::dvec3 scale = glm::exp(glm::dvec3(cloud.log_scales[index]));
    const ScreenCovariance cov = screen_covariance(frame.local_to_camera * *rotation, scale, t, camera);
    if (!finite(g.mean) || !std::isfinite(cov.xx + cov.xy + cov.yy + cov.det)) return culled(g, CullReason::non_finite);
    if (!dilate(g, cov, settings)) return g;
    if (!set_extent(g, camera)) return culled(g, CullReason::outside);
    g.colour = sh_colour(cloud, index, frame.sh_degree, local - frame.camera_local);
    return g;
}

}  // namespace detail

const char* to_string(CullReason reason) {
    switch (reason) {
        case CullReason::none:
            return "drawn";
        case CullReason::non_finite:
            return "non-finite";
        case CullReason::zero_rotation:
            return "zero rotation";
        case CullReason::near_plane:
            return "near plane";
        case CullReason::invisible:
            return "invisible";
        case CullReason::degenerate:
            return "degenerate";
        case CullReason::outside:
            return "outside";
    }
    return "unknown";
}

ReferenceCamera make_reference_camera(const engine::CameraView& view) {
    ReferenceCamera camera;
    camera.view = glm::dmat4(view.view);
    camera.position = glm::dvec3(glm::inverse(camera.view)[3]);
    camera.width = view.width;
    camera.height = view.height;
    camera.fx = camera.fy = 0.5 * view.height / std::tan(0.5 * static_cast<double>(view.fov_y));
    camera.cx = 0.5 * view.width;
    camera.cy = 0.5 * view.height;
    detail::check_camera(camera, "splat_lod::reference::make_reference_camera()");
    return camera;
}

ReferenceCamera scaled_camera(const ReferenceCamera& full, double render_scale) {
    const char* caller = "splat_lod::reference::scaled_camera()";
    if (!(render_scale > 0.0 && render_scale <= 1.0))
        engine::fail(std::string(caller) + ": render scale must be in (0, 1], got " + std::to_string(render_scale));
    detail::check_camera(full, caller);
    ReferenceCamera low = full;
    low.fx = full.fx * render_scale;
    low.fy = full.fy * render_scale;
    low.cx = full.cx * render_scale;
    low.cy = full.cy * render_scale;
    low.width = upscale::low_res_size(full.width, render_scale);
    low.height = upscale::low_res_size(full.height, render_scale);
    // The rounded-up size widens the field of view by up to one texel; the clamp stays the
    // output's (the full camera's own clamp if it has one), so Σ2D is exactly s² times the native.
    low.clamp_tan_x = full.jacobian_clamp_tan_x();
    low.clamp_tan_y = full.jacobian_clamp_tan_y();
    return low;
}

ProjectedGaussian project_gaussian(const SplatCloud& cloud, std::size_t index, const glm::dmat4& model,
                                   const ReferenceCamera& camera, const ReferenceSettings& settings,
                                   int sh_degree_cap) {
    detail::check_camera(camera, "splat_lod::reference::project_gaussian()");
    detail::check_settings(settings, "splat_lod::reference::project_gaussian()");
    const detail::InstanceFrame frame = detail::make_instance_frame(cloud, model, camera, settings, sh_degree_cap);
    return detail::project_in_frame(cloud, index, frame, camera, settings);
}

}  // namespace splat_lod::reference
