#pragma once
// Where a frame shows the borders between the world's chunks, for the profile's seam_ratio: the LOD
// image's error against the reference near the projected chunk borders, divided by its error
// elsewhere. A pixel shows the chunk whose square holds the point where the pixel's ray meets the
// terrain's height field (props and trees standing on it are not traced: they belong to the chunk
// under them); a pixel whose ray leaves the world without meeting the ground shows no chunk (sky).
// A pixel is in the border band when some pixel within `radius` pixels (Chebyshev) shows another
// chunk. GL-free.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/eval/image_metrics.h"

namespace sample_game {

inline constexpr int kSeamBandRadiusPx = 4;

// The height field on a regular grid over the world [−size/2, size/2]², bilinear between samples,
// with its lowest and highest sample (so that rays are clipped to the slab that holds the ground).
class HeightGrid {
public:
    HeightGrid(const std::function<float(float x, float z)>& height, float size_m, int cells = 1024);
    float size() const { return size_; }
    float height(float x, float z) const;  // clamped to the grid's edge outside the world
    float lowest() const { return lowest_; }
    float highest() const { return highest_; }

private:
    float size_, step_;
    int samples_;  // per side
    std::vector<float> heights_;
    float lowest_ = 0.0f, highest_ = 0.0f;
};

// The world's chunk grid: `count` × `count` squares of `chunk_size_m`, row-major from −x, −z
// (the generator's layout: chunk (i, j) covers [−size/2 + i·chunk, −size/2 + (i + 1)·chunk) in x).
struct ChunkGrid {
    float size_m = 0.0f, chunk_size_m = 1.0f;
    // Per grid cell, the cell index of the chunk that holds it when chunks span several cells (an
    // import's quadtree, ChunkEntry::span); empty: every cell its own chunk.
    std::vector<int> owner;
    int count() const;
    int chunk_at(float x, float z) const;  // −1 outside the world
};

// The manifest's grid, with the owners of cells that chunks of several cells hold.
ChunkGrid chunk_grid(const splat_lod::world::WorldManifest& manifest);

// Per pixel (row-major, top row first): the chunk it shows, −1 for none, and how far along the
// pixel's ray the ground is (m; −1 for none).
struct ChunkMap {
    int width = 0, height = 0;
    std::vector<int> chunk;
    std::vector<float> distance;
};

// Casts every pixel centre's ray of `camera` onto the ground: marched in steps growing with the
// distance (2 % of it, at least a tenth of the grid spacing), then refined by bisection.
ChunkMap chunk_map(const HeightGrid& ground, const ChunkGrid& chunks, const engine::CameraView& camera);

// 1 where a pixel showing a chunk has a pixel within `radius` showing another chunk.
std::vector<std::uint8_t> border_band(const ChunkMap& map, int radius = kSeamBandRadiusPx);

// Mean absolute error (over RGB) of `image` against `reference` in the band divided by that
// outside it, both over pixels that show a chunk; none when either part is empty or the error
// outside the band is 0. Throws engine::Error when the sizes differ.
std::optional<double> seam_ratio(const splat_lod::eval::FloatImage& image, const splat_lod::eval::FloatImage& reference,
                                 const ChunkMap& map, int radius = kSeamBandRadiusPx);

// seam_ratio with the distance held fixed: the band's error divided by the error that pixels outside
// the band at the same ground distance have (distance bins a sixteenth of an octave wide; the band's pixels in
// a bin without pixels outside the band are left out). Error against a supersampled reference grows
// by orders of magnitude from the near ground to the horizon (aliasing, not seams), and the projected
// borders crowd toward the horizon, so seam_ratio is large wherever the view sees both near ground and
// far chunks, with or without a seam; this ratio is about 1 there unless the borders themselves carry
// error. None when nothing is comparable or the comparable error outside the band is 0.
inline constexpr int kSeamDistanceBinsPerOctave = 16;
std::optional<double> seam_ratio_same_distance(const splat_lod::eval::FloatImage& image,
                                               const splat_lod::eval::FloatImage& reference, const ChunkMap& map,
                                               int radius = kSeamBandRadiusPx);

// What seam_ratio sees, as a picture: the error against the reference (mean over RGB, ×8, grey; white
// from 32/255 on), with the border band tinted red and pixels that show no chunk (sky) dimmed blue.
// Throws engine::Error when the sizes differ.
engine::Image seam_picture(const splat_lod::eval::FloatImage& image, const splat_lod::eval::FloatImage& reference,
                           const ChunkMap& map, int radius = kSeamBandRadiusPx);

}  // namespace sample_game
