// The splat frame's buffers and low-resolution images (frame_buffers.h).
#include "passes/frame_buffers.h"

#include <algorithm>

#include "engine/gl/compute_step.h"
#include "engine/gl/radix_sort.h"
#include "gpu/gpu_layout.h"

namespace splat_lod {
namespace {

constexpr std::uint32_t initial_keys_per_slot = 4;
constexpr std::uint32_t minimum_key_capacity = 1u << 16;

engine::gl::Buffer fixed_buffer(const char* label, std::size_t bytes) {
    engine::gl::Buffer buffer(label);
    buffer.storage(bytes);
    return buffer;
}

// `buffer` holding at least `bytes`: made anew with a quarter to spare when smaller, or when more
// than four times larger (a view that draws less), its contents not kept.
void fit(engine::gl::Buffer& buffer, std::size_t bytes, const char* label) {
    if (buffer && buffer.size() >= bytes && buffer.size() / 4 <= bytes) return;
    buffer = engine::gl::Buffer(engine::gl::NoCreate);
    buffer.ensure_size(bytes + bytes / 4, label);
}

}  // namespace

void FrameBuffers::ensure(std::uint32_t slots, std::uint32_t clusters, std::uint32_t tile_count) {
    if (!uniforms) {
        uniforms = fixed_buffer("splat frame uniforms", sizeof(gpu::FrameUniforms));
        counters = fixed_buffer("splat frame counters", sizeof(gpu::FrameCounters));
        args = fixed_buffer("splat dispatch args", sizeof(glm::uvec4));
        count = fixed_buffer("splat slot count", sizeof(std::uint32_t));
        budget = fixed_buffer("splat budget", sizeof(gpu::SplatBudgetState));
    }
    fit(projected, std::size_t(slots) * sizeof(gpu::ProjectedSplat), "splat projected");
    cluster_list.ensure_size(sizeof(glm::uvec4) + std::size_t(clusters) * sizeof(std::uint32_t), "splat cluster list");
    fit(tile_counts, (std::size_t(slots) + 1) * sizeof(std::uint32_t), "splat tile counts");
    tile_ranges.ensure_size(std::size_t(tile_count) * sizeof(glm::uvec2), "splat tile ranges");
    const std::uint32_t wanted =
        std::max({minimum_key_capacity, slots * initial_keys_per_slot, pending_growth + pending_growth / 4});
    const std::uint32_t capacity = std::min(wanted, engine::gl::RadixSort::max_sort_count());
    if (capacity > key_capacity || capacity < key_capacity / 4) {
        keys = engine::gl::Buffer(engine::gl::NoCreate);
        values = engine::gl::Buffer(engine::gl::NoCreate);
        keys.ensure_size(std::size_t(capacity) * sizeof(glm::uvec2), "splat tile keys");
        values.ensure_size(std::size_t(capacity) * sizeof(std::uint32_t), "splat tile values");
        key_capacity = capacity;
    }
    pending_growth = 0;
}

void FrameBuffers::clear(bool with_budget) {
    engine::gl::clear_to_zero(counters);
    if (with_budget) engine::gl::clear_to_zero(budget);
    engine::gl::clear_to_zero(tile_ranges);
    // Gaussians of skipped clusters are never visited: their tile counts stay 0.
    engine::gl::clear_to_zero(tile_counts);
    const glm::uvec4 no_clusters(0u, 1u, 1u, 0u);
    cluster_list.upload(0, sizeof(no_clusters), &no_clusters);
    engine::gl::memory_barrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

std::uint64_t FrameBuffers::bytes() const {
    return projected.size() + tile_counts.size() + keys.size() + values.size() + tile_ranges.size() +
           cluster_list.size();
}

void LowResImages::ensure(int w, int h) {
    if (width == w && height == h) return;
    const char* labels[] = {"splat low-res value", "splat low-res dx", "splat low-res dy", "splat low-res dxy"};
    for (int k = 0; k < 4; ++k) images[k] = engine::gl::texture_2d(GL_RGBA32F, w, h, labels[k]);
    front = engine::gl::texture_2d(GL_R32F, w, h, "splat low-res front depth");
    width = w;
    height = h;
}

std::uint64_t LowResImages::bytes() const {
    return std::uint64_t(width) * std::uint64_t(height) * (4 * 16 + 4);
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

}  // namespace splat_lod
