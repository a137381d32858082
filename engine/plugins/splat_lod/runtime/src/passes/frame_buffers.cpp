// The splat frame's buffers and low-resolution images (frame_buffers.h).
#include "passes/frame_buffers.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "engine/gl/compute_step.h"
#include "engine/gl/radix_sort.h"
#include "gpu/gpu_layout.h"

namespace splat_lod {
namespace {

constexpr std::uint32_t minimum_splat_capacity = 1u << 12;
constexpr std::uint32_t minimum_key_capacity = 1u << 14;
// Room beyond the need: a frame that projects more splats than the array holds runs steps 1–2 again,
// one that needs more keys only allocates them, so the splats get more.
constexpr double splat_spare = 0.25;
constexpr double key_spare = 1.0 / 16.0;

engine::gl::Buffer fixed_buffer(const char* label, std::size_t bytes) {
    engine::gl::Buffer buffer(label);
    buffer.storage(bytes);
    return buffer;
}

// A capacity for `need` elements: `capacity` while it holds them, is within `limit` and three quarters of
// it would not, else the need and `spare` of it more, at least `minimum` and at most `limit`.
std::uint32_t follow(std::uint32_t capacity, std::uint32_t need, double spare, std::uint32_t minimum,
                     std::uint32_t limit) {
    if (capacity >= need && capacity <= limit && (need >= capacity / 4 * 3 || capacity <= minimum)) return capacity;
    const double wanted = std::max<double>(minimum, std::ceil(need * (1.0 + spare)));
    return static_cast<std::uint32_t>(std::min<double>(wanted, limit));
}

}  // namespace

void FrameBuffers::ensure(std::uint32_t clusters, std::uint32_t tile_count) {
    if (!uniforms) {
        uniforms = fixed_buffer("splat frame uniforms", sizeof(gpu::FrameUniforms));
        counters = fixed_buffer("splat frame counters", sizeof(gpu::FrameCounters));
        counters_before = fixed_buffer("splat frame counters before the strip", sizeof(gpu::FrameCounters));
        args = fixed_buffer("splat dispatch args", sizeof(glm::uvec4));
        count = fixed_buffer("splat cluster count", sizeof(std::uint32_t));
        budget = fixed_buffer("splat budget", sizeof(gpu::SplatBudgetState));
    }
    cluster_list.ensure_size(sizeof(glm::uvec4) + std::size_t(clusters) * sizeof(std::uint32_t), "splat cluster list");
    cluster_pairs.ensure_size((std::size_t(clusters) + 1) * sizeof(std::uint32_t), "splat cluster pairs");
    cluster_splats.ensure_size(std::max<std::size_t>(clusters, 1) * sizeof(glm::uvec2), "splat cluster splats");
    cluster_rows.ensure_size(std::max<std::size_t>(clusters, 1) * sizeof(std::uint32_t), "splat cluster rows");
    tile_ranges.ensure_size(std::size_t(tile_count) * sizeof(glm::uvec2), "splat tile ranges");
    count.upload(0, sizeof(clusters), &clusters);
}

void FrameBuffers::ensure_splats(std::uint32_t splats, std::uint32_t most) {
    const std::uint32_t limit = std::min(std::max(splats, most), std::numeric_limits<std::uint32_t>::max() / 64);
    const std::uint32_t capacity = follow(splat_capacity, splats, splat_spare, minimum_splat_capacity, limit);
    if (capacity == splat_capacity && projected) return;
    projected = engine::gl::Buffer(engine::gl::NoCreate);
    projected.ensure_size(std::size_t(capacity) * sizeof(gpu::ProjectedSplat), "splat projected");
    splat_capacity = capacity;
}

void FrameBuffers::ensure_keys(std::uint32_t pairs, std::uint32_t words, std::uint32_t most) {
    const std::uint32_t limit = std::min(std::max(pairs, most), engine::gl::RadixSort::max_sort_count());
    const std::uint32_t capacity = follow(key_capacity, pairs, key_spare, minimum_key_capacity, limit);
    if (capacity == key_capacity && words == key_words && keys) return;
    keys = engine::gl::Buffer(engine::gl::NoCreate);
    values = engine::gl::Buffer(engine::gl::NoCreate);
    keys.ensure_size(std::size_t(capacity) * sizeof(std::uint32_t) * words, "splat tile keys");
    values.ensure_size(std::size_t(capacity) * sizeof(std::uint32_t), "splat tile values");
    key_capacity = capacity;
    key_words = words;
}

void FrameBuffers::clear(bool with_budget) {
    counters_kept_ = false;
    engine::gl::clear_to_zero(counters);
    if (with_budget) engine::gl::clear_to_zero(budget);
    engine::gl::clear_to_zero(cluster_rows);
    clear_selection();
}

void FrameBuffers::clear_strip() {
    engine::gl::memory_barrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the strip before wrote the counters
    if (!counters_kept_)
        engine::gl::copy_buffer(counters, counters_before, sizeof(gpu::FrameCounters));
    else
        engine::gl::copy_buffer(counters_before, counters, sizeof(gpu::FrameCounters));
    counters_kept_ = true;
    const std::uint32_t none = 0;
    counters.upload(offsetof(gpu::FrameCounters, projected), sizeof(none), &none);
    clear_selection();
}

void FrameBuffers::clear_selection() {
    engine::gl::clear_to_zero(tile_ranges);
    // Clusters step 1b does not project keep no pairs.
    engine::gl::clear_to_zero(cluster_pairs);
    const glm::uvec4 no_clusters(0u, 1u, 1u, 0u);
    cluster_list.upload(0, sizeof(no_clusters), &no_clusters);
    engine::gl::memory_barrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

std::uint64_t FrameBuffers::bytes() const {
    return projected.size() + cluster_pairs.size() + cluster_splats.size() + cluster_rows.size() + keys.size() +
           values.size() + tile_ranges.size() + cluster_list.size();
}

void LowResImages::ensure(int w, int h) {
    if (width == w && height == h) return;
    const char* labels[] = {"splat low-res value", "splat low-res dx", "splat low-res dy", "splat low-res dxy"};
    for (int k = 0; k < 4; ++k) images[k] = engine::gl::texture_2d(GL_RGBA32F, w, h, labels[k]);
    front = engine::gl::texture_2d(GL_RGBA32F, w, h, "splat low-res front depth");
    width = w;
    height = h;
}

std::uint64_t LowResImages::bytes() const {
    return std::uint64_t(width) * std::uint64_t(height) * (5 * 16);
}

upscale::GradientImage LowResImages::read_image() const {
    upscale::GradientImage image;
    if (width == 0) return image;
    image.width = width;
    image.height = height;
    std::vector<float>* channels[] = {&image.value, &image.dx, &image.dy, &image.dxy};
    const std::size_t floats = std::size_t(width) * std::size_t(height) * 4;
    engine::gl::memory_barrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    for (int k = 0; k < 4; ++k) {
        channels[k]->resize(floats);
        engine::gl::read_texture(images[k], GL_RGBA, floats, channels[k]->data());
    }
    return image;
}

std::vector<float> LowResImages::read_front_depth() const {
    std::vector<float> depth(std::size_t(width) * std::size_t(height));
    if (depth.empty()) return depth;
    engine::gl::memory_barrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    engine::gl::read_texture(front, GL_RED, depth.size(), depth.data());
    return depth;
}

void SplatDepthImage::ensure(int w, int h) {
    if (width == w && height == h) return;
    image = engine::gl::texture_2d(GL_RG32F, w, h, "splat depth");
    width = w;
    height = h;
}

std::uint64_t SplatDepthImage::bytes() const {
    return std::uint64_t(width) * std::uint64_t(height) * 8;
}

SplatDepth SplatDepthImage::read() const {
    SplatDepth depth;
    if (width == 0) return depth;
    depth.width = width;
    depth.height = height;
    std::vector<float> both(std::size_t(width) * std::size_t(height) * 2);
    engine::gl::memory_barrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    engine::gl::read_texture(image, GL_RG, both.size(), both.data());
    depth.median.resize(both.size() / 2);
    depth.expected.resize(both.size() / 2);
    for (std::size_t i = 0; i < depth.median.size(); ++i) {
        depth.median[i] = both[2 * i];
        depth.expected[i] = both[2 * i + 1];
    }
    return depth;
}

}  // namespace splat_lod
