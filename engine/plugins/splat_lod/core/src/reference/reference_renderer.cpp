// The per-image part of the reference renderer (docs/algorithms.md §1): project every Gaussian, sort the
// drawn ones front to back, bin them to 16-row bands and 16×16 tiles by their exact α ≥ 1/255
// bounding box, and blend each pixel. The binning only shortens the candidate lists; a pixel
// still tests every splat's pixel rectangle, so the image does not depend on the tile size.
// Optionally (ReferenceSettings::gradients) each pixel also gets the analytic image derivatives
// of the splat layer (docs/algorithms.md §5), the input of the gradient-aware upscaler.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <string>

#include "engine/core/error.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/parallel_for.h"
#include "splat_lod/core/upscale.h"

namespace splat_lod::reference {
namespace {

constexpr int kTileSize = 16;                   // band height and tile width, in pixels
constexpr std::size_t kProjectionChunk = 8192;  // Gaussians per projection task

struct DrawnSplat {
    glm::dvec2 mean{0.0};
    glm::dvec3 conic{0.0};
    glm::dvec3 colour{0.0};
    double opacity = 0.0;
    double depth = 0.0;
    PixelRect pixels;
    std::size_t instance = 0;
    std::size_t index = 0;
};

struct Projection {
    std::vector<DrawnSplat> splats;
    ReferenceStats stats;
};

void count(ReferenceStats& stats, CullReason reason) {
    ++stats.considered;
    switch (reason) {
        case CullReason::none:
            ++stats.drawn;
            break;
        case CullReason::non_finite:
            ++stats.non_finite_dropped;
            break;
        case CullReason::zero_rotation:
            ++stats.zero_rotation_dropped;
            break;
        case CullReason::near_plane:
            ++stats.culled_near;
            break;
        case CullReason::invisible:
            ++stats.culled_invisible;
            break;
        case CullReason::degenerate:
            ++stats.culled_degenerate;
            break;
        case CullReason::outside:
            ++stats.culled_outside;
            break;
    }
}

void add(ReferenceStats& total, const ReferenceStats& part) {
    total.considered += part.considered;
    total.non_finite_dropped += part.non_finite_dropped;
    total.zero_rotation_dropped += part.zero_rotation_dropped;
    total.culled_near += part.culled_near;
    total.culled_invisible += part.culled_invisible;
    total.culled_degenerate += part.culled_degenerate;
    total.culled_outside += part.culled_outside;
    total.drawn += part.drawn;
}

struct ProjectionTask {
    std::size_t instance = 0;
    std::size_t begin = 0;
    std::size_t end = 0;
};

// Projects every Gaussian of every instance. Tasks are concatenated in their (instance, index)
// order, so the result does not depend on the thread count.
Projection project_all(std::span<const ReferenceInstance> instances, const ReferenceCamera& camera,
                       const ReferenceSettings& settings, int threads) {
    std::vector<detail::InstanceFrame> frames(instances.size());
    std::vector<ProjectionTask> tasks;
    for (std::size_t i = 0; i < instances.size(); ++i) {
        const SplatCloud* cloud = instances[i].cloud;
        if (cloud == nullptr || cloud->empty()) continue;
        cloud->check_consistent();
        frames[i] =
            detail::make_instance_frame(*cloud, instances[i].model, camera, settings, instances[i].sh_degree_cap);
        for (std::size_t begin = 0; begin < cloud->size(); begin += kProjectionChunk)
            tasks.push_back({i, begin, std::min(cloud->size(), begin + kProjectionChunk)});
    }
    std::vector<Projection> parts(tasks.size());
    detail::parallel_for(tasks.size(), threads, [&](std::size_t t) {
        const ProjectionTask& task = tasks[t];
        const SplatCloud& cloud = *instances[task.instance].cloud;
        for (std::size_t index = task.begin; index < task.end; ++index) {
            const ProjectedGaussian g = detail::project_in_frame(cloud, index, frames[task.instance], camera, settings);
            count(parts[t].stats, g.cull);
            if (g.drawn())
                parts[t].splats.push_back(
                    {g.mean, g.conic, g.colour, g.opacity, g.depth, g.pixels, task.instance, index});
        }
    });
    Projection all;
    for (const Projection& part : parts) {
        add(all.stats, part.stats);
        all.splats.insert(all.splats.end(), part.splats.begin(), part.splats.end());
    }
    return all;
}

// Front to back; equal depths by (instance, index), a total order, hence deterministic.
void sort_front_to_back(std::vector<DrawnSplat>& splats) {
    std::sort(splats.begin(), splats.end(), [](const DrawnSplat& a, const DrawnSplat& b) {
        if (a.depth != b.depth) return a.depth < b.depth;
        if (a.instance != b.instance) return a.instance < b.instance;
        return a.index < b.index;
    });
}

// For each band of kTileSize rows, the splats whose pixel rectangle meets it, in depth order.
struct BandLists {
    std::vector<std::size_t> offsets;  // band b holds ids[offsets[b] .. offsets[b + 1])
    std::vector<std::uint32_t> ids;
};

BandLists bin_to_bands(const std::vector<DrawnSplat>& splats, int height) {
    const int bands = (height + kTileSize - 1) / kTileSize;
    BandLists lists;
    lists.offsets.assign(static_cast<std::size_t>(bands) + 1, 0);
    for (const DrawnSplat& s : splats)
        for (int b = s.pixels.y0 / kTileSize; b <= s.pixels.y1 / kTileSize; ++b)
            ++lists.offsets[static_cast<std::size_t>(b) + 1];
    for (std::size_t b = 1; b < lists.offsets.size(); ++b) lists.offsets[b] += lists.offsets[b - 1];
    lists.ids.resize(lists.offsets.back());
    std::vector<std::size_t> cursor(lists.offsets.begin(), lists.offsets.end() - 1);
    for (std::size_t id = 0; id < splats.size(); ++id)
        for (int b = splats[id].pixels.y0 / kTileSize; b <= splats[id].pixels.y1 / kTileSize; ++b)
            lists.ids[cursor[static_cast<std::size_t>(b)]++] = static_cast<std::uint32_t>(id);
    return lists;
}

// ∂/∂x, ∂/∂y and ∂²/∂x∂y of the splat-only (C.rgb, A) at one pixel, in pixels (docs/algorithms.md §5).
struct PixelDerivatives {
    glm::dvec4 dx{0.0};
    glm::dvec4 dy{0.0};
    glm::dvec4 dxy{0.0};
};

struct PixelResult {
    glm::dvec3 colour{0.0};
    double transmittance = 1.0;
    std::uint32_t contributors = 0;
    double depth_sum = 0.0;                                   // Σ dᵢαᵢTᵢ
    double median = std::numeric_limits<double>::infinity();  // where T first falls below ½
};

// One splat's term of Niedermayr et al. Eqs. 8–14 in the accumulated-alpha form of docs/algorithms.md §5, taken
// before the splat is blended: `transmittance` is still T = 1 − A of the splats in front. The
// exponent g = −½ dᵀ C d has g_x = −(Cxx dx + Cxy dy), g_y = −(Cxy dx + Cyy dy), g_xy = −Cxy;
// α is the clamped value and the clamp itself is not differentiated.
void accumulate_derivatives(PixelDerivatives& sum, const DrawnSplat& s, const glm::dvec2& d, double alpha,
                            double transmittance) {
    const double g_x = -(s.conic.x * d.x + s.conic.y * d.y);
    const double g_y = -(s.conic.y * d.x + s.conic.z * d.y);
    const double alpha_x = alpha * g_x;
    const double alpha_y = alpha * g_y;
    const double alpha_xy = alpha * (g_x * g_y - s.conic.y);
    const double a_x = sum.dx.w, a_y = sum.dy.w, a_xy = sum.dxy.w;  // of A before this splat
    const glm::dvec3 dx = s.colour * (alpha_x * transmittance - alpha * a_x);
    const glm::dvec3 dy = s.colour * (alpha_y * transmittance - alpha * a_y);
    const glm::dvec3 dxy = s.colour * (alpha_xy * transmittance - alpha_x * a_y - alpha_y * a_x - alpha * a_xy);
    sum.dx += glm::dvec4(dx, 0.0);
    sum.dy += glm::dvec4(dy, 0.0);
    sum.dxy += glm::dvec4(dxy, 0.0);
    // A ← A + α(1 − A), differentiated (Eq. 14 and its y and xy counterparts).
    sum.dx.w = a_x * (1.0 - alpha) + transmittance * alpha_x;
    sum.dy.w = a_y * (1.0 - alpha) + transmittance * alpha_y;
    sum.dxy.w = a_xy * (1.0 - alpha) - a_x * alpha_y - a_y * alpha_x + transmittance * alpha_xy;
}

// §1 per pixel: α = min(0.99, o·exp(−½ dᵀΣ2D⁻¹d)), skip α < 1/255, stop before T < 1e−4,
// C = Σ cᵢαᵢTᵢ (3DGS Eq. 3). Splats at or behind the mesh depth do not contribute. With
// `kGradients` the image derivatives are accumulated into `derivatives` over the same splats (same
// skips, same stops); without, the loop is the plain one and `derivatives` is not touched.
template <bool kGradients>
PixelResult blend_pixel(std::span<const std::uint32_t> ids, const std::vector<DrawnSplat>& splats, int x, int y,
                        double mesh_depth, PixelDerivatives* derivatives) {
    const glm::dvec2 centre(x + 0.5, y + 0.5);
    PixelResult result;
    for (const std::uint32_t id : ids) {
        const DrawnSplat& s = splats[id];
        if (s.depth >= mesh_depth) break;  // sorted by depth: every later splat is hidden too
        if (x < s.pixels.x0 || x > s.pixels.x1 || y < s.pixels.y0 || y > s.pixels.y1) continue;
        const glm::dvec2 d = centre - s.mean;
        const double power = -0.5 * (s.conic.x * d.x * d.x + 2.0 * s.conic.y * d.x * d.y + s.conic.z * d.y * d.y);
        const double alpha = std::min(kMaxAlpha, s.opacity * std::exp(power));
        if (alpha < kMinAlpha) continue;
        const double next = result.transmittance * (1.0 - alpha);
        if (next < kMinTransmittance) break;
        if constexpr (kGradients) accumulate_derivatives(*derivatives, s, d, alpha, result.transmittance);
        result.colour += s.colour * (alpha * result.transmittance);
        result.depth_sum += s.depth * (alpha * result.transmittance);
        if (result.transmittance >= 0.5 && next < 0.5) result.median = s.depth;
        result.transmittance = next;
        ++result.contributors;
    }
    return result;
}

struct RasterInputs {
    const std::vector<DrawnSplat>& splats;
    const BandLists& bands;
    const MeshLayer* mesh;
    glm::dvec3 background;
    bool gradients;
};

void store_gradients(const PixelResult& r, const PixelDerivatives& d, std::size_t pixel, ReferenceImage& image) {
    const glm::dvec4 value(r.colour, 1.0 - r.transmittance);
    for (glm::length_t c = 0; c < 4; ++c) {
        const std::size_t i = 4 * pixel + static_cast<std::size_t>(c);
        image.splat[i] = value[c];
        image.splat_dx[i] = d.dx[c];
        image.splat_dy[i] = d.dy[c];
        image.splat_dxy[i] = d.dxy[c];
    }
}

void rasterise_band(const RasterInputs& in, int band, ReferenceImage& image) {
    const auto first =
        in.bands.ids.begin() + static_cast<std::ptrdiff_t>(in.bands.offsets[static_cast<std::size_t>(band)]);
    const auto last =
        in.bands.ids.begin() + static_cast<std::ptrdiff_t>(in.bands.offsets[static_cast<std::size_t>(band) + 1]);
    const int y0 = band * kTileSize, y1 = std::min(image.height, y0 + kTileSize);
    std::vector<std::uint32_t> tile;
    for (int x0 = 0; x0 < image.width; x0 += kTileSize) {
        const int x1 = std::min(image.width, x0 + kTileSize);
        tile.clear();
        std::copy_if(first, last, std::back_inserter(tile),
                     [&](std::uint32_t id) { return in.splats[id].pixels.x0 < x1 && in.splats[id].pixels.x1 >= x0; });
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const std::size_t p = image.pixel_index(x, y);
                const double mesh_depth = in.mesh ? in.mesh->depth[p] : std::numeric_limits<double>::infinity();
                PixelResult r;
                if (in.gradients) {
                    PixelDerivatives derivatives;
                    r = blend_pixel<true>(tile, in.splats, x, y, mesh_depth, &derivatives);
                    store_gradients(r, derivatives, p, image);
                } else {
                    r = blend_pixel<false>(tile, in.splats, x, y, mesh_depth, nullptr);
                }
                const glm::dvec3 behind = in.mesh ? in.mesh->colour[p] : in.background;
                const glm::dvec3 c = r.colour + r.transmittance * behind;
                image.rgb[3 * p] = c.x;
                image.rgb[3 * p + 1] = c.y;
                image.rgb[3 * p + 2] = c.z;
                image.alpha[p] = 1.0 - r.transmittance;
                image.contributors[p] = r.contributors;
                image.depth_median[p] = r.median;
                if (r.contributors > 0) image.depth_expected[p] = r.depth_sum / (1.0 - r.transmittance);
            }
    }
}

void check_inputs(const ReferenceCamera& camera, const ReferenceSettings& settings, const MeshLayer* mesh) {
    const char* caller = "splat_lod::reference::render_reference()";
    detail::check_camera(camera, caller);
    detail::check_settings(settings, caller);
    if (mesh == nullptr) return;
    const std::size_t pixels = static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height);
    if (mesh->width != camera.width || mesh->height != camera.height || mesh->depth.size() != pixels ||
        mesh->colour.size() != pixels)
        engine::fail(std::string(caller) + ": mesh layer is " + std::to_string(mesh->width) + "x" +
                     std::to_string(mesh->height) + " with " + std::to_string(mesh->depth.size()) +
                     " depths, camera is " + std::to_string(camera.width) + "x" + std::to_string(camera.height));
}

}  // namespace

ReferenceImage render_reference(std::span<const ReferenceInstance> instances, const ReferenceCamera& camera,
                                const ReferenceSettings& settings, const MeshLayer* mesh, ReferenceStats* stats) {
    check_inputs(camera, settings, mesh);
    const int threads = detail::resolve_thread_count(settings.threads);
    Projection projection = project_all(instances, camera, settings, threads);
    sort_front_to_back(projection.splats);
    const BandLists bands = bin_to_bands(projection.splats, camera.height);

    ReferenceImage image;
    image.width = camera.width;
    image.height = camera.height;
    const std::size_t pixels = static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height);
    image.rgb.assign(3 * pixels, 0.0);
    image.alpha.assign(pixels, 0.0);
    image.contributors.assign(pixels, 0);
    image.depth_median.assign(pixels, std::numeric_limits<double>::infinity());
    image.depth_expected.assign(pixels, std::numeric_limits<double>::infinity());
    if (settings.gradients)
        for (std::vector<double>* channel : {&image.splat, &image.splat_dx, &image.splat_dy, &image.splat_dxy})
            channel->assign(4 * pixels, 0.0);
    const RasterInputs inputs{projection.splats, bands, mesh, settings.background, settings.gradients};
    detail::parallel_for(bands.offsets.size() - 1, threads,
                         [&](std::size_t band) { rasterise_band(inputs, static_cast<int>(band), image); });
    if (stats) *stats = projection.stats;
    return image;
}

ReferenceImage render_reference(std::span<const ReferenceInstance> instances, const engine::CameraView& camera,
                                const ReferenceSettings& settings, const MeshLayer* mesh, ReferenceStats* stats) {
    return render_reference(instances, make_reference_camera(camera), settings, mesh, stats);
}

engine::Image to_image8(const ReferenceImage& image) {
    engine::Image out;
    out.width = image.width;
    out.height = image.height;
    out.rgba.resize(4 * image.alpha.size());
    // v > 0 ? … : 0 also maps a NaN (which the renderer never produces) to black, not to UB.
    const auto to8 = [](double v) {
        return static_cast<std::uint8_t>(std::lround((v > 0.0 ? std::min(v, 1.0) : 0.0) * 255.0));
    };
    for (std::size_t p = 0; p < image.alpha.size(); ++p) {
        for (std::size_t c = 0; c < 3; ++c) out.rgba[4 * p + c] = to8(image.rgb[3 * p + c]);
        out.rgba[4 * p + 3] = 255;
    }
    return out;
}

upscale::GradientImage to_gradient_image(const ReferenceImage& image) {
    const std::size_t size = 4 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    if (image.splat.size() != size || image.splat_dx.size() != size || image.splat_dy.size() != size ||
        image.splat_dxy.size() != size)
        engine::fail("splat_lod::reference::to_gradient_image(): the " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) +
                     " image has no gradients (render it with ReferenceSettings::gradients)");
    const auto to_float = [](const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); };
    upscale::GradientImage out;
    out.width = image.width;
    out.height = image.height;
    out.value = to_float(image.splat);
    out.dx = to_float(image.splat_dx);
    out.dy = to_float(image.splat_dy);
    out.dxy = to_float(image.splat_dxy);
    return out;
}

}  // namespace splat_lod::reference
