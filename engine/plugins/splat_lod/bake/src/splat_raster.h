#pragma once
// The differentiable CPU rasteriser of the bake's refinement (docs/algorithms.md §4 step 7). The geometry of
// a camera's splats (mean, conic, depth order, pixel rectangle) is fixed for the whole refinement,
// so it is projected and binned once into a RasterFrame; each iteration then only needs the image
// from the per-splat colour and opacity (render_forward) and the gradients of a loss with respect
// to them (render_backward). The forward is exactly the per-pixel blending of the reference
// renderer (§1), in the same order and with the same arithmetic, so a frame built from the
// reference projection renders the reference image.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::bake {

inline constexpr int kRasterTileSize = 16;  // tiles are kRasterTileSize × kRasterTileSize pixels

struct RasterSplat {
    glm::dvec2 mean{0.0};    // pixels, top-left origin (ProjectedGaussian::mean)
    glm::dvec3 conic{0.0};   // inverse of the dilated 2D covariance (xx, xy, yy)
    double opacity = 0.0;    // activated opacity o as projected (a starting value)
    glm::dvec3 colour{0.0};  // RGB as projected (a starting value)
    double depth = 0.0;
    std::uint32_t id = 0;         // the caller's Gaussian index; ties in depth are broken by id
    reference::PixelRect pixels;  // inclusive pixel rectangle (ProjectedGaussian::pixels)
};

// One (tile, splat) pair: what the tile's pixels need of the splat's geometry. Stored in tile order,
// so that a tile reads its splats contiguously rather than gathering them from the depth-sorted list.
struct RasterTileEntry {
    glm::dvec2 mean{0.0};
    glm::dvec3 conic{0.0};
    std::uint32_t splat = 0;                      // position in RasterFrame::splats()
    std::uint8_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the splat's rectangle ∩ the tile, tile-local, inclusive
};

// The splats of one camera sorted front to back by (depth, id), stably, with rectangles clipped to
// the image, and binned to tiles. Only the geometry is held: colour and opacity are read at
// forward/backward time from spans indexed like splats(), so the caller updates them without
// rebuilding the frame. A splat whose rectangle misses the image stays in splats() but reaches no
// pixel (its gradients are 0). Rectangles are not grown when an opacity grows: like the selection
// (§4.7), the pixels a splat may reach are fixed while the frame is in use; re-project to update them.
class RasterFrame {
public:
    // Throws engine::Error for a non-positive image size or a splat with a non-finite mean, conic or
    // depth.
    RasterFrame(std::vector<RasterSplat> splats, int width, int height);

    const std::vector<RasterSplat>& splats() const { return splats_; }
    int width() const { return width_; }
    int height() const { return height_; }
    int tiles_x() const { return tiles_x_; }
    int tiles_y() const { return tiles_y_; }
    std::size_t tile_count() const { return tile_offsets_.size() - 1; }

    // The splats whose rectangle meets `tile` (row-major), front to back.
    std::span<const RasterTileEntry> tile_entries(std::size_t tile) const;
    // Where tile_entries(tile) starts among all (tile, splat) pairs; tile_entry_begin(tile_count())
    // is their total.
    std::size_t tile_entry_begin(std::size_t tile) const { return tile_offsets_[tile]; }

    // The projected starting values, indexed like splats().
    std::vector<glm::dvec3> colours() const;
    std::vector<double> opacities() const;

private:
    std::vector<RasterSplat> splats_;
    int width_ = 0;
    int height_ = 0;
    int tiles_x_ = 0;
    int tiles_y_ = 0;
    std::vector<std::size_t> tile_offsets_;  // tile t holds entries_[offsets[t] .. offsets[t + 1])
    std::vector<RasterTileEntry> entries_;

    void bin_to_tiles();
};

struct RasterImage {
    int width = 0;
    int height = 0;
    std::vector<double> rgb;            // 3 per pixel, row-major, top row first: C + T·background
    std::vector<double> transmittance;  // T after the last blended splat (1 − the reference's alpha)

    std::size_t pixel_index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    }
    glm::dvec3 colour_at(int x, int y) const {
        const std::size_t i = 3 * pixel_index(x, y);
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
};

// §1 per pixel: α = min(0.99, o·exp(−½ dᵀΣ2D⁻¹d)), skip α < 1/255, stop before T < 1e−4,
// C = Σ cᵢαᵢTᵢ + T_end·background. `colour` and `opacity` hold one finite value per splats()[i];
// threads 0 means std::thread::hardware_concurrency(). Throws engine::Error on a size mismatch or a
// non-finite value.
RasterImage render_forward(const RasterFrame& frame, std::span<const glm::dvec3> colour,
                           std::span<const double> opacity, const glm::dvec3& background, int threads = 0);

// The gradients of a loss L with respect to every splat's colour and opacity, given dL/dC per pixel
// (`dl_drgb`, laid out like RasterImage::rgb), with the 1/255 skips, the early stop and the pixel
// rectangles held fixed (§4.7): ∂C/∂cᵢ = αᵢTᵢ; ∂C/∂αᵢ = cᵢTᵢ − Rᵢ/(1 − αᵢ) with
// Rᵢ = Σ_{j>i} c_jα_jT_j + T_end·background; ∂αᵢ/∂oᵢ = exp(power) while o·exp(power) < 0.99 and 0
// at the clamp. Overwrites d_colour[i] and d_opacity[i] for every splats()[i]. The result is the
// same, bit for bit, for any thread count: each tile sums into its own buffer and the tiles are
// reduced in a fixed order.
void render_backward(const RasterFrame& frame, std::span<const glm::dvec3> colour, std::span<const double> opacity,
                     const glm::dvec3& background, std::span<const double> dl_drgb, std::span<glm::dvec3> d_colour,
                     std::span<double> d_opacity, int threads = 0);

// Projects Gaussians `indices` of `cloud` (identity model) with the reference projection and keeps
// the drawn ones, in the order of `indices`, with id = the Gaussian's index. opacity is the drawn
// opacity (× the mip factor when settings.mip_filter is on) and colour the clamped SH colour.
// threads 0 means settings.threads, then std::thread::hardware_concurrency(). Throws engine::Error
// for an index out of range or an invalid camera or settings.
std::vector<RasterSplat> project_for_raster(const SplatCloud& cloud, std::span<const std::uint32_t> indices,
                                            const reference::ReferenceCamera& camera,
                                            const reference::ReferenceSettings& settings, int threads = 0);

// Chain rule to the stored parameters (§1 activation). opacity = sigmoid(logit), so
// ∂o/∂logit = o(1 − o), evaluated without cancellation for large |logit|. With the mip filter on,
// the drawn opacity is m·sigmoid(logit): pass d_opacity·m.
double d_logit_from_d_opacity(double d_opacity, double logit);

// colour = max(0, C0·dc + view-dependent SH + 0.5) per channel (`colour_before_clamp` is that sum,
// e.g. reference::sh_colour_unclamped), so ∂colour/∂dc = C0 = Y_0^0 where the sum is ≥ 0 and 0
// where it is negative (3DGS's convention at the kink).
glm::dvec3 d_sh_dc_from_d_colour(const glm::dvec3& d_colour, const glm::dvec3& colour_before_clamp);

}  // namespace splat_lod::bake
