#pragma once
// The double-precision CPU reference renderer: the oracle that the GPU passes are tested against.
// It implements the forward model of docs/algorithms.md §1 exactly and nothing else (no LOD
// selection): activation, culling, EWA projection with the 0.3 px dilation, SH colour, the
// α ≥ 1/255 extent, and front-to-back blending with the 1e−4 transmittance stop. The camera and
// pixel conventions are those of engine/render/camera.h. Bad input (NaN/Inf, zero quaternions,
// degenerate covariances) is dropped and counted, never drawn, and never crashes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::upscale {
struct GradientImage;  // splat_lod/core/upscale.h
}

namespace splat_lod::reference {

// The constants of docs/algorithms.md §1, named once.
inline constexpr double kMinAlpha = 1.0 / 255.0;     // skip below; also the visibility cull
inline constexpr double kMaxAlpha = 0.99;            // per-splat α cap
inline constexpr double kMinTransmittance = 1e-4;    // stop before T would fall below
inline constexpr double kJacobianClampFactor = 1.3;  // x/z, y/z clamped to ±1.3·tan(fov/2)

// One splat component: its cloud and the world matrix of its node (affine).
struct ReferenceInstance {
    const SplatCloud* cloud = nullptr;
    glm::dmat4 model{1.0};
    int sh_degree_cap = kMaxShDegree;
};

struct ReferenceSettings {
    double znear = 0.2;          // cull z ≤ znear (z = −z_view); CameraView::znear is for GL only
    double dilation = 0.3;       // added to the diagonal of Σ2D (the EWA low-pass)
    bool mip_filter = false;     // opacity × sqrt(det Σ2D / det(Σ2D + dilation·I))
    glm::dvec3 background{0.0};  // composited behind the splats when there is no mesh layer
    int sh_degree_cap = kMaxShDegree;
    int threads = 0;  // 0: std::thread::hardware_concurrency()
    // Also output the splat-only colour and alpha with their x, y and xy image derivatives
    // (docs/algorithms.md §5), the input of the spline upscaler. Off: no extra memory and no extra work.
    bool gradients = false;
};

// The camera in double precision. View coordinates follow camera.h (looking down −Z, +Y up);
// the renderer works in the derived "image-aligned" frame x right, y down, z = −z_view forward,
// in which the projection is u = cx + fx·x/z, v = cy + fy·y/z and 3DGS's Jacobian applies as is.
struct ReferenceCamera {
    glm::dmat4 view{1.0};      // world → view
    glm::dvec3 position{0.0};  // camera centre in world space
    double fx = 1.0;
    double fy = 1.0;
    double cx = 0.5;
    double cy = 0.5;
    int width = 1;
    int height = 1;
    // When > 0, used instead of tan_half_fov_x()/tan_half_fov_y() in the ±1.3·tan Jacobian clamp
    // (§1). A low-resolution render for upscaling sets them to the output camera's values: its
    // image is rounded up to whole texels, so its own field of view is slightly wider, and the
    // clamp must not move with it. Must be finite and not negative.
    double clamp_tan_x = 0.0;
    double clamp_tan_y = 0.0;

    double tan_half_fov_x() const { return 0.5 * width / fx; }
    double tan_half_fov_y() const { return 0.5 * height / fy; }
    double jacobian_clamp_tan_x() const { return clamp_tan_x > 0.0 ? clamp_tan_x : tan_half_fov_x(); }
    double jacobian_clamp_tan_y() const { return clamp_tan_y > 0.0 ? clamp_tan_y : tan_half_fov_y(); }
};

// fx = fy = (H/2)/tan(fov_y/2) and the principal point at the image centre (camera.h), computed in
// double from the float fields; the centre is taken from inverse(view), the authoritative matrix.
ReferenceCamera make_reference_camera(const engine::CameraView& camera);

// The camera that rasterises the low-resolution image for render scale s (upscale.h): fx, fy, cx,
// cy × s, size upscale::low_res_size(W, s) × upscale::low_res_size(H, s), and the Jacobian clamp of
// `full` (clamp_tan_x/y), so a Gaussian's projection is the native one scaled by s: mean × s
// (i.e. (native + 0.5)·s − 0.5 in texel-centre coordinates) and Σ2D × s² before the dilation
// (render with dilation 0.3·s² for the native blur, docs/algorithms.md §5). Throws engine::Error for s
// outside (0, 1] or NaN, or an invalid `full`.
ReferenceCamera scaled_camera(const ReferenceCamera& full, double render_scale);

enum class CullReason : std::uint8_t {
    none,           // drawn
    non_finite,     // NaN/Inf in an attribute, the model matrix, or a derived value
    zero_rotation,  // quaternion of (near) zero length
    near_plane,     // z ≤ znear: behind the camera, on its centre, or too close
    invisible,      // opacity ≤ 1/255 (after the mip filter when it is on)
    degenerate,     // det of the (dilated) Σ2D ≤ 0, or a singular model matrix
    outside,        // the α ≥ 1/255 bounding box covers no pixel centre
};
const char* to_string(CullReason reason);

// Inclusive range of the pixels whose centres lie in the extent's bounding box, clipped.
struct PixelRect {
    int x0 = 0;
    int y0 = 0;
    int x1 = -1;
    int y1 = -1;
};

// The result of the per-Gaussian step (what a GPU preprocess pass writes). A culled Gaussian keeps
// the fields computed before the test that culled it (an `outside` one has mean, cov2d, conic).
struct ProjectedGaussian {
    CullReason cull = CullReason::none;
    double depth = 0.0;      // z = −z_view
    double opacity = 0.0;    // sigmoid(logit), × the mip factor when that is on
    glm::dvec2 mean{0.0};    // μ2D in pixels, top-left origin
    glm::dvec3 cov2d{0.0};   // dilated Σ2D as (xx, xy, yy)
    glm::dvec3 conic{0.0};   // its inverse as (xx, xy, yy)
    glm::dvec3 colour{0.0};  // SH + 0.5, clamped at 0 (no upper clamp)
    glm::dvec2 extent{0.0};  // half-widths of the bounding box of dᵀΣ2D⁻¹d ≤ 2·ln(255·o)
    PixelRect pixels;

    bool drawn() const { return cull == CullReason::none; }
};

// Projects Gaussian `index` of `cloud` placed by `model`: world mean model·p, world covariance
// M R S Sᵀ Rᵀ Mᵀ with M the linear part of `model`. The SH degree used is
// min(cloud.sh_degree, sh_degree_cap, settings.sh_degree_cap), evaluated along M⁻¹(μ_world − c),
// the camera→mean direction in the cloud's frame: R⁻¹·d for a rotation with uniform scale; under
// non-uniform scale or shear, the local direction that the model maps onto the viewing ray.
ProjectedGaussian project_gaussian(const SplatCloud& cloud, std::size_t index, const glm::dmat4& model,
                                   const ReferenceCamera& camera, const ReferenceSettings& settings,
                                   int sh_degree_cap = kMaxShDegree);

// The real SH basis values Y_k(d) for k = 1..15 in 3DGS order up to `degree` (entry 0 unused, higher
// entries zero), d a unit vector.
std::array<double, 16> sh_basis(const glm::dvec3& d, int degree);
// SH colour of Gaussian `index` seen along `direction` (in the cloud's frame, any length > 0):
// real SH of degree `degree` with 3DGS's constants, + 0.5, clamped at 0.
glm::dvec3 sh_colour(const SplatCloud& cloud, std::size_t index, int degree, const glm::dvec3& direction);
// The same before the clamp at 0: what the colour is linear in (the bake differentiates it).
glm::dvec3 sh_colour_unclamped(const SplatCloud& cloud, std::size_t index, int degree, const glm::dvec3& direction);

// What the mesh pass left behind, per pixel (row-major, top row first): the view depth z = −z_view
// of the nearest surface (+inf where there is none) and the display colour there (the background
// where there is no surface). Splats composite over it: final = C + T·colour.
struct MeshLayer {
    int width = 0;
    int height = 0;
    std::vector<double> depth;
    std::vector<glm::dvec3> colour;
};

struct ReferenceImage {
    int width = 0;
    int height = 0;
    std::vector<double> rgb;                  // 3 per pixel, row-major, top row first
    std::vector<double> alpha;                // A = 1 − T
    std::vector<std::uint32_t> contributors;  // splats blended into the pixel
    // The splats' view depth z = −z_view per pixel, +inf where there is none: `depth_median` is the
    // depth of the splat with which the accumulated opacity first reaches ½ (none where it never
    // does), `depth_expected` the opacity-weighted mean Σ dᵢαᵢTᵢ / A over the splats blended (none
    // where none was). Splats behind the mesh layer are not blended, so neither sees them.
    std::vector<double> depth_median{};
    std::vector<double> depth_expected{};
    // With ReferenceSettings::gradients only (empty otherwise), 4 per pixel as (r, g, b, A): the
    // splat-only premultiplied colour C = Σ cᵢαᵢTᵢ and alpha A = 1 − T, before the background or
    // the mesh colour is added, and their derivatives in pixels of this image (x right, y down).
    // Zero where no splat was blended.
    std::vector<double> splat{};
    std::vector<double> splat_dx{};
    std::vector<double> splat_dy{};
    std::vector<double> splat_dxy{};

    std::size_t pixel_index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    }
    glm::dvec3 colour_at(int x, int y) const {
        const std::size_t i = 3 * pixel_index(x, y);
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
    double alpha_at(int x, int y) const { return alpha[pixel_index(x, y)]; }
    std::uint32_t contributors_at(int x, int y) const { return contributors[pixel_index(x, y)]; }
};

// Where every considered Gaussian went: considered = the sum of the other fields.
struct ReferenceStats {
    std::size_t considered = 0;
    std::size_t non_finite_dropped = 0;
    std::size_t zero_rotation_dropped = 0;
    std::size_t culled_near = 0;
    std::size_t culled_invisible = 0;
    std::size_t culled_degenerate = 0;
    std::size_t culled_outside = 0;
    std::size_t drawn = 0;
};

// Renders the instances (null or empty clouds are skipped). Depth ties are broken by (instance
// position in the span, Gaussian index), so the output is deterministic for any thread count.
// Throws engine::Error for an invalid camera or a mesh layer of the wrong size.
ReferenceImage render_reference(std::span<const ReferenceInstance> instances, const ReferenceCamera& camera,
                                const ReferenceSettings& settings, const MeshLayer* mesh = nullptr,
                                ReferenceStats* stats = nullptr);
ReferenceImage render_reference(std::span<const ReferenceInstance> instances, const engine::CameraView& camera,
                                const ReferenceSettings& settings, const MeshLayer* mesh = nullptr,
                                ReferenceStats* stats = nullptr);

// 8-bit RGBA: round(clamp(v, 0, 1)·255) per channel (§1 "Output values"), alpha 255.
engine::Image to_image8(const ReferenceImage& image);

// The splat-only channels and their derivatives (`splat`, `splat_dx`, …) as the float image the
// upscalers take. Throws engine::Error when the image was rendered without gradients.
upscale::GradientImage to_gradient_image(const ReferenceImage& image);

}  // namespace splat_lod::reference
