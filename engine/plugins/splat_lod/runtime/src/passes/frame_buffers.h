#pragma once
// The splat frame's own GPU memory, apart from the scene's Gaussians: the per-frame buffers the steps
// write and read (sized for the resident Gaussians and the raster's tiles, kept between frames and grown
// when a frame needs more) and, below render scale 1, the low-resolution images with their derivatives.
#include <array>
#include <cstdint>
#include <vector>

#include "engine/gl/objects.h"
#include "splat_lod/core/upscale.h"

namespace splat_lod {

struct FrameBuffers {
    engine::gl::Buffer uniforms{engine::gl::NoCreate};      // gpu::FrameUniforms
    engine::gl::Buffer counters{engine::gl::NoCreate};      // gpu::FrameCounters
    engine::gl::Buffer args{engine::gl::NoCreate};          // indirect dispatch arguments of steps 5 on
    engine::gl::Buffer count{engine::gl::NoCreate};         // the frame's slot count, for the scan
    engine::gl::Buffer budget{engine::gl::NoCreate};        // gpu::SplatBudgetState
    engine::gl::Buffer projected{engine::gl::NoCreate};     // one gpu::ProjectedSplat per slot
    engine::gl::Buffer cluster_list{engine::gl::NoCreate};  // dispatch arguments + the clusters kept
    engine::gl::Buffer tile_counts{engine::gl::NoCreate};   // per slot, then its key offset; total at [slots]
    engine::gl::Buffer tile_ranges{engine::gl::NoCreate};   // per tile, its range of sorted keys
    engine::gl::Buffer keys{engine::gl::NoCreate}, values{engine::gl::NoCreate};  // tile-splat pairs
    std::uint32_t key_capacity = 0;
    std::uint32_t pending_growth = 0;  // keys a past frame needed beyond the capacity

    // Sizes the buffers for `slots` splat slots (GpuScene::slot_count), `clusters` in the cluster list
    // and `tile_count` tiles, with room for the keys a past frame needed (pending_growth), at most the
    // sort's limit. They grow with room to spare and shrink when a quarter would do, so that they follow
    // what the view can draw.
    void ensure(std::uint32_t slots, std::uint32_t clusters, std::uint32_t tile_count);
    // The counters, the budget's histograms (with a budget), the tile ranges and counts at zero, and the
    // cluster list empty, before step 1 fills them.
    void clear(bool with_budget);
    // The per-frame buffers that grow with the scene and the view.
    std::uint64_t bytes() const;
};

// The raster's output below render scale 1: value, d/dx, d/dy, d²/dxdy (RGBA32F) and the front depth
// (R32F), kept while the raster size stays the same.
struct LowResImages {
    int width = 0, height = 0;
    std::array<engine::gl::Texture, 4> images{
        engine::gl::Texture(engine::gl::NoCreate), engine::gl::Texture(engine::gl::NoCreate),
        engine::gl::Texture(engine::gl::NoCreate), engine::gl::Texture(engine::gl::NoCreate)};
    engine::gl::Texture front{engine::gl::NoCreate};

    void ensure(int w, int h);
    std::uint64_t bytes() const;
    // Read back, blocking: the image with its derivatives (rows top first) and the front depths.
    upscale::GradientImage read_image() const;
    std::vector<float> read_front_depth() const;
};

}  // namespace splat_lod
