#include "sample_game/harness/chunk_borders.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "engine/core/error.h"

namespace sample_game {

HeightGrid::HeightGrid(const std::function<float(float x, float z)>& height, float size_m, int cells)
    : size_(size_m), step_(size_m / static_cast<float>(cells)), samples_(cells + 1) {
    if (!(size_m > 0.0f) || cells < 1) engine::fail("HeightGrid: the world size and the cell count must be positive");
    heights_.resize(static_cast<std::size_t>(samples_) * static_cast<std::size_t>(samples_));
    lowest_ = std::numeric_limits<float>::max();
    highest_ = std::numeric_limits<float>::lowest();
    for (int j = 0; j < samples_; ++j)
        for (int i = 0; i < samples_; ++i) {
            const float h =
                height(-0.5f * size_ + static_cast<float>(i) * step_, -0.5f * size_ + static_cast<float>(j) * step_);
            heights_[static_cast<std::size_t>(j) * static_cast<std::size_t>(samples_) + static_cast<std::size_t>(i)] =
                h;
            lowest_ = std::min(lowest_, h);
            highest_ = std::max(highest_, h);
        }
}

float HeightGrid::height(float x, float z) const {
    const float last = static_cast<float>(samples_ - 1);
    const float u = std::clamp((x + 0.5f * size_) / step_, 0.0f, last),
                v = std::clamp((z + 0.5f * size_) / step_, 0.0f, last);
    const int i = std::min(static_cast<int>(u), samples_ - 2), j = std::min(static_cast<int>(v), samples_ - 2);
    const float fu = u - static_cast<float>(i), fv = v - static_cast<float>(j);
    const auto at = [&](int a, int b) {
        return heights_[static_cast<std::size_t>(b) * static_cast<std::size_t>(samples_) + static_cast<std::size_t>(a)];
    };
    return (1.0f - fv) * ((1.0f - fu) * at(i, j) + fu * at(i + 1, j)) +
           fv * ((1.0f - fu) * at(i, j + 1) + fu * at(i + 1, j + 1));
}

int ChunkGrid::count() const {
    return std::max(1, static_cast<int>(std::lround(size_m / chunk_size_m)));
}

int ChunkGrid::chunk_at(float x, float z) const {
    const float u = (x + 0.5f * size_m) / chunk_size_m, v = (z + 0.5f * size_m) / chunk_size_m;
    const int n = count();
    if (!(u >= 0.0f && v >= 0.0f && u <= static_cast<float>(n) && v <= static_cast<float>(n))) return -1;
    const int cell = std::min(static_cast<int>(v), n - 1) * n + std::min(static_cast<int>(u), n - 1);
    return owner.empty() ? cell : owner[static_cast<std::size_t>(cell)];
}

ChunkGrid chunk_grid(const splat_lod::world::WorldManifest& m) {
    ChunkGrid grid{m.size_m, m.chunk_size_m, {}};
    const int n = grid.count();
    const bool spans = std::any_of(m.chunks.begin(), m.chunks.end(), [](const auto& c) { return c.span > 0; });
    if (!spans) return grid;
    grid.owner.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
    for (std::size_t k = 0; k < grid.owner.size(); ++k) grid.owner[k] = static_cast<int>(k);
    for (const splat_lod::world::ChunkEntry& c : m.chunks) {
        const glm::ivec2 low = c.cell + glm::ivec2(n / 2);
        const int side = 1 << c.span;
        for (int z = low.y; z < low.y + side && z < n; ++z)
            for (int x = low.x; x < low.x + side && x < n; ++x)
                if (x >= 0 && z >= 0) grid.owner[static_cast<std::size_t>(z * n + x)] = low.y * n + low.x;
    }
    return grid;
}

namespace {

// [t0, t1] of the ray inside the box; empty (t0 > t1) when it misses.
void clip_to_box(const glm::vec3& origin, const glm::vec3& dir, const glm::vec3& lo, const glm::vec3& hi, float& t0,
                 float& t1) {
    t0 = 0.0f;
    t1 = std::numeric_limits<float>::max();
    for (int a = 0; a < 3; ++a) {
        if (std::abs(dir[a]) < 1e-12f) {
            if (origin[a] < lo[a] || origin[a] > hi[a]) t0 = 1.0f, t1 = 0.0f;
            continue;
        }
        float near_t = (lo[a] - origin[a]) / dir[a], far_t = (hi[a] - origin[a]) / dir[a];
        if (near_t > far_t) std::swap(near_t, far_t);
        t0 = std::max(t0, near_t);
        t1 = std::min(t1, far_t);
    }
}

// Distance along the unit ray to the ground, or a negative value when it never meets it.
float hit_ground(const HeightGrid& ground, const glm::vec3& origin, const glm::vec3& dir, float min_step) {
    const float half = 0.5f * ground.size();
    float t0 = 0.0f, t1 = 0.0f;
    clip_to_box(origin, dir, {-half, ground.lowest() - 0.01f, -half}, {half, ground.highest() + 0.01f, half}, t0, t1);
    if (t0 > t1) return -1.0f;
    const auto above = [&](float t) {
        const glm::vec3 p = origin + t * dir;
        return p.y - ground.height(p.x, p.z);
    };
    float t = t0;
    if (above(t) <= 0.0f) return t;
    while (t < t1) {
        const float next = std::min(t1, t + std::max(min_step, 0.02f * t));
        if (above(next) <= 0.0f) {
            float a = t, b = next;  // above at a, at or below at b
            for (int k = 0; k < 24; ++k) {
                const float m = 0.5f * (a + b);
                (above(m) > 0.0f ? a : b) = m;
            }
            return b;
        }
        t = next;
    }
    return -1.0f;
}

}  // namespace

ChunkMap chunk_map(const HeightGrid& ground, const ChunkGrid& chunks, const engine::CameraView& camera) {
    ChunkMap map;
    map.width = camera.width;
    map.height = camera.height;
    map.chunk.assign(static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height), -1);
    map.distance.assign(map.chunk.size(), -1.0f);
    const glm::mat3 to_world = glm::mat3(glm::inverse(camera.view));
    const float f = camera.focal_length();
    const glm::vec2 c = camera.principal_point();
    const float min_step = 0.1f * ground.size() / 1024.0f;
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            const glm::vec3 view_dir{(static_cast<float>(x) + 0.5f - c.x) / f,
                                     -(static_cast<float>(y) + 0.5f - c.y) / f, -1.0f};
            const glm::vec3 dir = glm::normalize(to_world * view_dir);
            const float t = hit_ground(ground, camera.position, dir, min_step);
            if (t < 0.0f) continue;
            const glm::vec3 p = camera.position + t * dir;
            const std::size_t i =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(map.width) + static_cast<std::size_t>(x);
            map.chunk[i] = chunks.chunk_at(p.x, p.z);
            if (map.chunk[i] >= 0) map.distance[i] = t;
        }
    return map;
}

namespace {

// Sliding minimum (or maximum) over ±radius along rows (step 1) or columns (step = width).
std::vector<int> window_extreme(const std::vector<int>& in, int width, int height, int radius, bool along_rows,
                                bool maximum) {
    std::vector<int> out(in.size());
    const int lines = along_rows ? height : width, length = along_rows ? width : height;
    for (int line = 0; line < lines; ++line)
        for (int i = 0; i < length; ++i) {
            int best = maximum ? INT_MIN : INT_MAX;
            for (int k = std::max(0, i - radius); k <= std::min(length - 1, i + radius); ++k) {
                const int value = along_rows ? in[static_cast<std::size_t>(line * width + k)]
                                             : in[static_cast<std::size_t>(k * width + line)];
                best = maximum ? std::max(best, value) : std::min(best, value);
            }
            out[static_cast<std::size_t>(along_rows ? line * width + i : i * width + line)] = best;
        }
    return out;
}

}  // namespace

std::vector<std::uint8_t> border_band(const ChunkMap& map, int radius) {
    // Sky counts as no chunk: INT_MAX for the minimum, −1 for the maximum, so it never differs.
    std::vector<int> for_min(map.chunk.size()), for_max = map.chunk;
    for (std::size_t i = 0; i < map.chunk.size(); ++i) for_min[i] = map.chunk[i] < 0 ? INT_MAX : map.chunk[i];
    const auto lowest = window_extreme(window_extreme(for_min, map.width, map.height, radius, true, false), map.width,
                                       map.height, radius, false, false);
    const auto highest = window_extreme(window_extreme(for_max, map.width, map.height, radius, true, true), map.width,
                                        map.height, radius, false, true);
    std::vector<std::uint8_t> band(map.chunk.size(), 0);
    for (std::size_t i = 0; i < band.size(); ++i)
        band[i] = map.chunk[i] >= 0 && (lowest[i] < map.chunk[i] || highest[i] > map.chunk[i]) ? 1 : 0;
    return band;
}

namespace {

void check_sizes(const char* what, const splat_lod::eval::FloatImage& image,
                 const splat_lod::eval::FloatImage& reference, const ChunkMap& map) {
    if (image.width != reference.width || image.height != reference.height || image.width != map.width ||
        image.height != map.height)
        engine::fail(std::string(what) + ": the image is " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + ", the reference " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + ", the chunk map " + std::to_string(map.width) + "x" +
                     std::to_string(map.height));
}

// Mean absolute error over RGB of pixel i.
double pixel_error(const splat_lod::eval::FloatImage& image, const splat_lod::eval::FloatImage& reference,
                   std::size_t i) {
    double e = 0.0;
    for (std::size_t c = 0; c < 3; ++c) e += std::abs(double(image.rgb[3 * i + c]) - double(reference.rgb[3 * i + c]));
    return e / 3.0;
}

}  // namespace

std::optional<double> seam_ratio(const splat_lod::eval::FloatImage& image, const splat_lod::eval::FloatImage& reference,
                                 const ChunkMap& map, int radius) {
    check_sizes("seam_ratio", image, reference, map);
    const std::vector<std::uint8_t> band = border_band(map, radius);
    double error[2] = {0.0, 0.0};
    std::size_t pixels[2] = {0, 0};
    for (std::size_t i = 0; i < band.size(); ++i) {
        if (map.chunk[i] < 0) continue;
        error[band[i]] += pixel_error(image, reference, i);
        ++pixels[band[i]];
    }
    if (pixels[0] == 0 || pixels[1] == 0 || error[0] <= 0.0) return std::nullopt;
    return (error[1] / static_cast<double>(pixels[1])) / (error[0] / static_cast<double>(pixels[0]));
}

std::optional<double> seam_ratio_same_distance(const splat_lod::eval::FloatImage& image,
                                               const splat_lod::eval::FloatImage& reference, const ChunkMap& map,
                                               int radius) {
    check_sizes("seam_ratio_same_distance", image, reference, map);
    if (map.distance.size() != map.chunk.size())
        engine::fail("seam_ratio_same_distance: the chunk map has no distances");
    const std::vector<std::uint8_t> band = border_band(map, radius);
    // Per distance bin: error and pixel count inside (1) and outside (0) the band.
    struct Bin {
        double error[2] = {0.0, 0.0};
        std::size_t pixels[2] = {0, 0};
    };
    std::map<int, Bin> bins;
    for (std::size_t i = 0; i < band.size(); ++i) {
        if (map.chunk[i] < 0 || !(map.distance[i] > 0.0f)) continue;
        const int key = static_cast<int>(std::floor(kSeamDistanceBinsPerOctave * std::log2(double{map.distance[i]})));
        Bin& bin = bins[key];
        bin.error[band[i]] += pixel_error(image, reference, i);
        ++bin.pixels[band[i]];
    }
    double actual = 0.0, expected = 0.0;
    for (const auto& [key, bin] : bins) {
        if (bin.pixels[0] == 0 || bin.pixels[1] == 0) continue;
        actual += bin.error[1];
        expected += static_cast<double>(bin.pixels[1]) * bin.error[0] / static_cast<double>(bin.pixels[0]);
    }
    if (!(expected > 0.0)) return std::nullopt;
    return actual / expected;
}

engine::Image seam_picture(const splat_lod::eval::FloatImage& image, const splat_lod::eval::FloatImage& reference,
                           const ChunkMap& map, int radius) {
    check_sizes("seam_picture", image, reference, map);
    const std::vector<std::uint8_t> band = border_band(map, radius);
    engine::Image picture{map.width, map.height, std::vector<std::uint8_t>(band.size() * 4, 255)};
    for (std::size_t i = 0; i < band.size(); ++i) {
        const double grey = std::min(255.0, 8.0 * 255.0 * pixel_error(image, reference, i));
        const auto g = static_cast<std::uint8_t>(std::lround(grey));
        std::uint8_t* px = &picture.rgba[4 * i];
        if (map.chunk[i] < 0) {
            px[0] = static_cast<std::uint8_t>(g / 2), px[1] = static_cast<std::uint8_t>(g / 2);
            px[2] = static_cast<std::uint8_t>(std::min(255, 64 + g / 2));
        } else if (band[i]) {
            px[0] = static_cast<std::uint8_t>(std::min(255, 96 + g)), px[1] = g, px[2] = g;
        } else {
            px[0] = px[1] = px[2] = g;
        }
    }
    return picture;
}

}  // namespace sample_game
