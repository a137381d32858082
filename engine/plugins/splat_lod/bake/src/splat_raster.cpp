// The bake's differentiable rasteriser (docs/algorithms.md §1 forward, §4 step 7 backward). The per-pixel
// arithmetic is the reference renderer's blend_pixel, written in the same order, so the forward
// image equals the reference image and the backward differentiates exactly what is drawn.
#include "splat_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/core/error.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/parallel_for.h"

namespace splat_lod::bake {
namespace {

using reference::kMaxAlpha;
using reference::kMinAlpha;
using reference::kMinTransmittance;

constexpr std::size_t kProjectionChunk = 8192;  // Gaussians per projection task
// Y_0^0 in double, the value the reference SH evaluation multiplies the DC term by (kShC0 is its
// float rounding).
constexpr double kShC0Double = 0.28209479177387814;
// exp() is skipped where power < ln(kMinAlpha / o) − this margin, i.e. where α < 1/255 for certain:
// far above exp()'s rounding error, so the skip never changes which splats blend.
constexpr double kSkipPowerMargin = 1e-9;

bool finite(const glm::dvec2& v) {
    return std::isfinite(v.x) && std::isfinite(v.y);
}
bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// What a tile reads of one splat, gathered contiguously once per tile for its 256 pixels.
struct TileSplat {
    glm::dvec2 mean{0.0};
    glm::dvec3 conic{0.0};
    glm::dvec3 colour{0.0};
    double opacity = 0.0;
    double skip_power = 0.0;  // below it, α < 1/255 without evaluating exp()
};

constexpr int kTilePixels = kRasterTileSize * kRasterTileSize;
constexpr std::size_t kPrefetchDistance = 16;  // entries ahead: enough to hide a cache miss

// One tile's splats and, for each of its pixels, the splats whose rectangle holds that pixel, front
// to back. Bucketing by pixel once per tile replaces a rectangle test per (pixel, splat of the
// tile): with thousands of pixel-sized splats per tile, that test costs more than exp().
struct TileWork {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // pixel range [x0, x1) × [y0, y1)
    std::vector<TileSplat> splats;
    std::vector<std::size_t> pixel_offsets;   // pixel p of the tile: pixel_splats[offsets[p] .. offsets[p + 1])
    std::vector<std::uint32_t> pixel_splats;  // positions in `splats`
    std::vector<std::size_t> cursor;          // scratch of the bucketing

    std::span<const std::uint32_t> candidates(int x, int y) const {
        const std::size_t p = static_cast<std::size_t>((y - y0) * kRasterTileSize + (x - x0));
        return std::span<const std::uint32_t>(pixel_splats)
            .subspan(pixel_offsets[p], pixel_offsets[p + 1] - pixel_offsets[p]);
    }
};

// Calls body(tile pixel) for every pixel of the entry's rectangle within the tile.
template <typename Body>
void for_each_tile_pixel(const RasterTileEntry& e, const Body& body) {
    for (int y = e.y0; y <= e.y1; ++y)
        for (int x = e.x0; x <= e.x1; ++x) body(static_cast<std::size_t>(y * kRasterTileSize + x));
}

void prepare_tile(const RasterFrame& frame, std::size_t tile, std::span<const glm::dvec3> colour,
                  std::span<const double> opacity, TileWork& work) {
    const int tx = static_cast<int>(tile % static_cast<std::size_t>(frame.tiles_x()));
    const int ty = static_cast<int>(tile / static_cast<std::size_t>(frame.tiles_x()));
    work.x0 = tx * kRasterTileSize;
    work.y0 = ty * kRasterTileSize;
    work.x1 = std::min(frame.width(), work.x0 + kRasterTileSize);
    work.y1 = std::min(frame.height(), work.y0 + kRasterTileSize);
    const std::span<const RasterTileEntry> entries = frame.tile_entries(tile);
    work.splats.clear();
    work.pixel_offsets.assign(kTilePixels + 1, 0);
    for (std::size_t k = 0; k < entries.size(); ++k) {
        // colour and opacity are indexed in depth order, which jumps across memory from one entry to
        // the next: ask for them a few entries ahead.
        if (k + kPrefetchDistance < entries.size()) {
            __builtin_prefetch(&colour[entries[k + kPrefetchDistance].splat]);
            __builtin_prefetch(&opacity[entries[k + kPrefetchDistance].splat]);
        }
        const RasterTileEntry& e = entries[k];
        const double o = opacity[e.splat];
        // For o ≤ 0 every α is below 1/255: a skip power of +inf skips them all.
        const double skip =
            o > 0.0 ? std::log(kMinAlpha / o) - kSkipPowerMargin : std::numeric_limits<double>::infinity();
        work.splats.push_back({e.mean, e.conic, colour[e.splat], o, skip});
        for_each_tile_pixel(e, [&](std::size_t p) { ++work.pixel_offsets[p + 1]; });
    }
    for (std::size_t p = 1; p < work.pixel_offsets.size(); ++p) work.pixel_offsets[p] += work.pixel_offsets[p - 1];
    work.pixel_splats.resize(work.pixel_offsets.back());
    work.cursor.assign(work.pixel_offsets.begin(), work.pixel_offsets.end() - 1);
    for (std::size_t k = 0; k < entries.size(); ++k)
        for_each_tile_pixel(
            entries[k], [&](std::size_t p) { work.pixel_splats[work.cursor[p]++] = static_cast<std::uint32_t>(k); });
}

// §1's α of splat s at pixel (x, y), whose rectangle holds the pixel: false when α < 1/255.
// `falloff` receives exp(power), `alpha` the clamped α. The arithmetic is blend_pixel's.
inline bool splat_alpha(const TileSplat& s, int x, int y, double& alpha, double& falloff) {
    const glm::dvec2 d = glm::dvec2(x + 0.5, y + 0.5) - s.mean;
    const double power = -0.5 * (s.conic.x * d.x * d.x + 2.0 * s.conic.y * d.x * d.y + s.conic.z * d.y * d.y);
    if (power < s.skip_power) return false;
    falloff = std::exp(power);
    alpha = std::min(kMaxAlpha, s.opacity * falloff);
    return alpha >= kMinAlpha;
}

void forward_tile(const TileWork& work, const glm::dvec3& background, RasterImage& image) {
    for (int y = work.y0; y < work.y1; ++y)
        for (int x = work.x0; x < work.x1; ++x) {
            glm::dvec3 colour(0.0);
            double transmittance = 1.0;
            for (const std::uint32_t k : work.candidates(x, y)) {
                const TileSplat& s = work.splats[k];
                double alpha = 0.0, falloff = 0.0;
                if (!splat_alpha(s, x, y, alpha, falloff)) continue;
                const double next = transmittance * (1.0 - alpha);
                if (next < kMinTransmittance) break;
                colour += s.colour * (alpha * transmittance);
                transmittance = next;
            }
            const glm::dvec3 c = colour + transmittance * background;
            const std::size_t p = image.pixel_index(x, y);
            image.rgb[3 * p] = c.x;
            image.rgb[3 * p + 1] = c.y;
            image.rgb[3 * p + 2] = c.z;
            image.transmittance[p] = transmittance;
        }
}

// A splat blended into the pixel being differentiated: its position in the tile, α, the
// transmittance in front of it, and ∂α/∂o.
struct Contribution {
    std::uint32_t k = 0;
    double alpha = 0.0;
    double transmittance = 0.0;
    double d_alpha_d_opacity = 0.0;
};

// Replays the pixel's forward walk, then goes back to front with the scalar g·R (g = dL/dC), which
// is all that ∂L/∂αᵢ = g·cᵢTᵢ − g·Rᵢ/(1 − αᵢ) needs of Rᵢ (§4.7).
void backward_pixel(const TileWork& work, int x, int y, const glm::dvec3& g, const glm::dvec3& background,
                    std::vector<Contribution>& blended, glm::dvec3* d_colour, double* d_opacity) {
    blended.clear();
    double transmittance = 1.0;
    for (const std::uint32_t k : work.candidates(x, y)) {
        const TileSplat& s = work.splats[k];
        double alpha = 0.0, falloff = 0.0;
        if (!splat_alpha(s, x, y, alpha, falloff)) continue;
        const double next = transmittance * (1.0 - alpha);
        if (next < kMinTransmittance) break;
        // Below the clamp α = o·falloff; at it α is constant in o.
        const double d_alpha_d_opacity = s.opacity * falloff < kMaxAlpha ? falloff : 0.0;
        blended.push_back({k, alpha, transmittance, d_alpha_d_opacity});
        transmittance = next;
    }
    double g_dot_rest = transmittance * glm::dot(g, background);  // g·R for the last blended splat
    for (auto it = blended.rbegin(); it != blended.rend(); ++it) {
        const TileSplat& s = work.splats[it->k];
        const double weight = it->alpha * it->transmittance;
        const double g_dot_colour = glm::dot(g, s.colour);
        d_colour[it->k] += g * weight;
        const double d_alpha = g_dot_colour * it->transmittance - g_dot_rest / (1.0 - it->alpha);
        d_opacity[it->k] += d_alpha * it->d_alpha_d_opacity;
        g_dot_rest += g_dot_colour * weight;
    }
}

void backward_tile(const TileWork& work, int width, const glm::dvec3& background, std::span<const double> dl_drgb,
                   std::vector<Contribution>& blended, glm::dvec3* d_colour, double* d_opacity) {
    for (int y = work.y0; y < work.y1; ++y)
        for (int x = work.x0; x < work.x1; ++x) {
            const std::size_t p =
                3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x));
            const glm::dvec3 g(dl_drgb[p], dl_drgb[p + 1], dl_drgb[p + 2]);
            backward_pixel(work, x, y, g, background, blended, d_colour, d_opacity);
        }
}

void check_values(const RasterFrame& frame, std::span<const glm::dvec3> colour, std::span<const double> opacity,
                  const glm::dvec3& background, const char* caller) {
    const std::size_t n = frame.splats().size();
    if (colour.size() != n || opacity.size() != n)
        engine::fail(std::string(caller) + ": the frame has " + std::to_string(n) + " splats, got " +
                     std::to_string(colour.size()) + " colours and " + std::to_string(opacity.size()) + " opacities");
    for (std::size_t i = 0; i < n; ++i)
        if (!finite(colour[i]) || !std::isfinite(opacity[i]))
            engine::fail(std::string(caller) + ": splat " + std::to_string(i) + " (id " +
                         std::to_string(frame.splats()[i].id) + ") has a non-finite colour or opacity");
    if (!finite(background)) engine::fail(std::string(caller) + ": the background is not finite");
}

std::size_t pixel_count(const RasterFrame& frame) {
    return static_cast<std::size_t>(frame.width()) * static_cast<std::size_t>(frame.height());
}

// The inclusive rectangle clipped to the image; x0 > x1 or y0 > y1 when nothing is left.
reference::PixelRect clip(const reference::PixelRect& r, int width, int height) {
    return {std::max(r.x0, 0), std::max(r.y0, 0), std::min(r.x1, width - 1), std::min(r.y1, height - 1)};
}

bool is_empty(const reference::PixelRect& r) {
    return r.x0 > r.x1 || r.y0 > r.y1;
}

}  // namespace

RasterFrame::RasterFrame(std::vector<RasterSplat> splats, int width, int height)
    : splats_(std::move(splats)), width_(width), height_(height) {
    const std::string caller = "splat_lod::bake::RasterFrame";
    if (width <= 0 || height <= 0)
        engine::fail(caller + ": image size must be positive, got " + std::to_string(width) + "x" +
                     std::to_string(height));
    for (const RasterSplat& s : splats_)
        if (!finite(s.mean) || !finite(s.conic) || !std::isfinite(s.depth))
            engine::fail(caller + ": splat id " + std::to_string(s.id) + " has a non-finite mean, conic or depth");
    if (splats_.size() > std::numeric_limits<std::uint32_t>::max())
        engine::fail(caller + ": " + std::to_string(splats_.size()) + " splats do not fit 32-bit indices");
    // Sorting 8-byte positions rather than the splats themselves; the position is the last key, so
    // the order is the stable one.
    std::vector<std::uint32_t> order(splats_.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        const RasterSplat &sa = splats_[a], &sb = splats_[b];
        if (sa.depth != sb.depth) return sa.depth < sb.depth;
        if (sa.id != sb.id) return sa.id < sb.id;
        return a < b;
    });
    std::vector<RasterSplat> sorted;
    sorted.reserve(splats_.size());
    for (const std::uint32_t i : order) sorted.push_back(splats_[i]);
    splats_ = std::move(sorted);
    for (RasterSplat& s : splats_) s.pixels = clip(s.pixels, width, height);

    bin_to_tiles();
}

// Counting sort into tiles: splats are visited front to back, so each tile's list is in depth order.
void RasterFrame::bin_to_tiles() {
    tiles_x_ = (width_ + kRasterTileSize - 1) / kRasterTileSize;
    tiles_y_ = (height_ + kRasterTileSize - 1) / kRasterTileSize;
    tile_offsets_.assign(static_cast<std::size_t>(tiles_x_) * static_cast<std::size_t>(tiles_y_) + 1, 0);
    const auto for_each_tile = [&](const RasterSplat& s, const auto& body) {
        if (is_empty(s.pixels)) return;
        for (int ty = s.pixels.y0 / kRasterTileSize; ty <= s.pixels.y1 / kRasterTileSize; ++ty)
            for (int tx = s.pixels.x0 / kRasterTileSize; tx <= s.pixels.x1 / kRasterTileSize; ++tx)
                body(static_cast<std::size_t>(ty) * static_cast<std::size_t>(tiles_x_) + static_cast<std::size_t>(tx),
                     tx, ty);
    };
    for (const RasterSplat& s : splats_) for_each_tile(s, [&](std::size_t t, int, int) { ++tile_offsets_[t + 1]; });
    for (std::size_t t = 1; t < tile_offsets_.size(); ++t) tile_offsets_[t] += tile_offsets_[t - 1];
    entries_.resize(tile_offsets_.back());
    std::vector<std::size_t> cursor(tile_offsets_.begin(), tile_offsets_.end() - 1);
    for (std::size_t i = 0; i < splats_.size(); ++i) {
        const RasterSplat& s = splats_[i];
        for_each_tile(s, [&](std::size_t t, int tx, int ty) {
            const int x0 = tx * kRasterTileSize, y0 = ty * kRasterTileSize;
            const auto local = [](int v, int origin) {
                return static_cast<std::uint8_t>(std::clamp(v - origin, 0, kRasterTileSize - 1));
            };
            entries_[cursor[t]++] = {s.mean,
                                     s.conic,
                                     static_cast<std::uint32_t>(i),
                                     local(s.pixels.x0, x0),
                                     local(s.pixels.y0, y0),
                                     local(s.pixels.x1, x0),
                                     local(s.pixels.y1, y0)};
        });
    }
}

std::span<const RasterTileEntry> RasterFrame::tile_entries(std::size_t tile) const {
    return std::span<const RasterTileEntry>(entries_).subspan(tile_offsets_[tile],
                                                              tile_offsets_[tile + 1] - tile_offsets_[tile]);
}

std::vector<glm::dvec3> RasterFrame::colours() const {
    std::vector<glm::dvec3> out;
    out.reserve(splats_.size());
    for (const RasterSplat& s : splats_) out.push_back(s.colour);
    return out;
}

std::vector<double> RasterFrame::opacities() const {
    std::vector<double> out;
    out.reserve(splats_.size());
    for (const RasterSplat& s : splats_) out.push_back(s.opacity);
    return out;
}

RasterImage render_forward(const RasterFrame& frame, std::span<const glm::dvec3> colour,
                           std::span<const double> opacity, const glm::dvec3& background, int threads) {
    check_values(frame, colour, opacity, background, "splat_lod::bake::render_forward()");
    RasterImage image;
    image.width = frame.width();
    image.height = frame.height();
    image.rgb.assign(3 * pixel_count(frame), 0.0);
    image.transmittance.assign(pixel_count(frame), 1.0);
    const auto rasterise = [&](std::size_t tile) {
        thread_local TileWork work;
        prepare_tile(frame, tile, colour, opacity, work);
        forward_tile(work, background, image);
    };
    reference::detail::parallel_for(frame.tile_count(), reference::detail::resolve_thread_count(threads), rasterise);
    return image;
}

void render_backward(const RasterFrame& frame, std::span<const glm::dvec3> colour, std::span<const double> opacity,
                     const glm::dvec3& background, std::span<const double> dl_drgb, std::span<glm::dvec3> d_colour,
                     std::span<double> d_opacity, int threads) {
    const char* caller = "splat_lod::bake::render_backward()";
    check_values(frame, colour, opacity, background, caller);
    const std::size_t n = frame.splats().size();
    if (dl_drgb.size() != 3 * pixel_count(frame) || d_colour.size() != n || d_opacity.size() != n)
        engine::fail(std::string(caller) + ": expected " + std::to_string(3 * pixel_count(frame)) +
                     " dL/dC values and " + std::to_string(n) + " gradient slots, got " +
                     std::to_string(dl_drgb.size()) + ", " + std::to_string(d_colour.size()) + " and " +
                     std::to_string(d_opacity.size()));
    // One gradient slot per (tile, splat) pair: a tile writes only its own slots, whatever thread
    // runs it, and the reduction below visits the slots in one fixed order.
    const std::size_t entries = frame.tile_entry_begin(frame.tile_count());
    std::vector<glm::dvec3> entry_colour(entries, glm::dvec3(0.0));
    std::vector<double> entry_opacity(entries, 0.0);
    const auto differentiate = [&](std::size_t tile) {
        thread_local TileWork work;
        thread_local std::vector<Contribution> blended;
        prepare_tile(frame, tile, colour, opacity, work);
        const std::size_t begin = frame.tile_entry_begin(tile);
        backward_tile(work, frame.width(), background, dl_drgb, blended, entry_colour.data() + begin,
                      entry_opacity.data() + begin);
    };
    reference::detail::parallel_for(frame.tile_count(), reference::detail::resolve_thread_count(threads),
                                    differentiate);
    std::fill(d_colour.begin(), d_colour.end(), glm::dvec3(0.0));
    std::fill(d_opacity.begin(), d_opacity.end(), 0.0);
    for (std::size_t tile = 0; tile < frame.tile_count(); ++tile) {
        const std::span<const RasterTileEntry> tile_entries = frame.tile_entries(tile);
        const std::size_t begin = frame.tile_entry_begin(tile);
        for (std::size_t k = 0; k < tile_entries.size(); ++k) {
            d_colour[tile_entries[k].splat] += entry_colour[begin + k];
            d_opacity[tile_entries[k].splat] += entry_opacity[begin + k];
        }
    }
}

std::vector<RasterSplat> project_for_raster(const SplatCloud& cloud, std::span<const std::uint32_t> indices,
                                            const reference::ReferenceCamera& camera,
                                            const reference::ReferenceSettings& settings, int threads) {
    const char* caller = "splat_lod::bake::project_for_raster()";
    reference::detail::check_camera(camera, caller);
    reference::detail::check_settings(settings, caller);
    cloud.check_consistent();
    for (const std::uint32_t index : indices)
        if (index >= cloud.size())
            engine::fail(std::string(caller) + ": Gaussian index " + std::to_string(index) + " is out of range (" +
                         std::to_string(cloud.size()) + " Gaussians)");
    const reference::detail::InstanceFrame instance =
        reference::detail::make_instance_frame(cloud, glm::dmat4(1.0), camera, settings, kMaxShDegree);
    const std::size_t chunks = (indices.size() + kProjectionChunk - 1) / kProjectionChunk;
    std::vector<std::vector<RasterSplat>> parts(chunks);
    const int workers = reference::detail::resolve_thread_count(threads > 0 ? threads : settings.threads);
    reference::detail::parallel_for(chunks, workers, [&](std::size_t chunk) {
        const std::size_t end = std::min(indices.size(), (chunk + 1) * kProjectionChunk);
        for (std::size_t k = chunk * kProjectionChunk; k < end; ++k) {
            const reference::ProjectedGaussian g =
                reference::detail::project_in_frame(cloud, indices[k], instance, camera, settings);
            if (g.drawn())
                parts[chunk].push_back({g.mean, g.conic, g.opacity, g.colour, g.depth, indices[k], g.pixels});
        }
    });
    std::vector<RasterSplat> splats;
    for (const auto& part : parts) splats.insert(splats.end(), part.begin(), part.end());
    return splats;
}

double d_logit_from_d_opacity(double d_opacity, double logit) {
    // σ(l)·σ(−l) = σ(l)(1 − σ(l)), each factor in its overflow-free branch.
    const auto sigmoid = [](double v) {
        if (v >= 0.0) return 1.0 / (1.0 + std::exp(-v));
        const double e = std::exp(v);
        return e / (1.0 + e);
    };
    return d_opacity * sigmoid(logit) * sigmoid(-logit);
}

glm::dvec3 d_sh_dc_from_d_colour(const glm::dvec3& d_colour, const glm::dvec3& colour_before_clamp) {
    glm::dvec3 out(0.0);
    for (int c = 0; c < 3; ++c) out[c] = colour_before_clamp[c] >= 0.0 ? kShC0Double * d_colour[c] : 0.0;
    return out;
}

}  // namespace splat_lod::bake
