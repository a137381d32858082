#pragma once
// The splat frame's own GPU memory, apart from the scene's Gaussians: the per-frame buffers the steps
// write and read (sized for the resident Gaussians and the raster's tiles, kept between frames and grown
// when a frame needs more) and, below render scale 1, the low-resolution images with their derivatives.
#include <array>
#include <cstdint>
#include <vector>

#include "engine/gl/objects.h"
#include "splat_lod/core/upscale.h"
#include "splat_lod/splat_renderer.h"

namespace splat_lod {

struct FrameBuffers {
    engine::gl::Buffer uniforms{engine::gl::NoCreate};         // gpu::FrameUniforms
    engine::gl::Buffer counters{engine::gl::NoCreate};         // gpu::FrameCounters
    engine::gl::Buffer counters_before{engine::gl::NoCreate};  // a copy from before the strip being selected
    engine::gl::Buffer args{engine::gl::NoCreate};             // indirect dispatch arguments of steps 5 on
    engine::gl::Buffer count{engine::gl::NoCreate};            // the scene's cluster count, for the scan
    engine::gl::Buffer budget{engine::gl::NoCreate};           // gpu::SplatBudgetState
    engine::gl::Buffer projected{engine::gl::NoCreate};        // splat_capacity gpu::ProjectedSplat, dense
    engine::gl::Buffer cluster_list{engine::gl::NoCreate};     // dispatch arguments + the clusters kept
    engine::gl::Buffer cluster_pairs{engine::gl::NoCreate};    // per cluster, then its first key; total at [C]
    engine::gl::Buffer cluster_splats{engine::gl::NoCreate};   // per cluster, its run of projected splats
    engine::gl::Buffer cluster_rows{engine::gl::NoCreate};     // per cluster, in strips: the rows it reaches
    engine::gl::Buffer tile_ranges{engine::gl::NoCreate};      // per tile, its range of sorted keys
    engine::gl::Buffer keys{engine::gl::NoCreate}, values{engine::gl::NoCreate};  // tile-splat pairs
    engine::gl::Buffer picks{engine::gl::NoCreate};  // gpu::SplatPicks, made on the first pick
    std::uint32_t splat_capacity = 0;
    std::uint32_t key_capacity = 0;
    std::uint32_t key_words = 2;  // 32-bit words of a key (RadixSort's SortJob::key_words)

    // Sizes the buffers that follow the scene and the raster: `clusters` (the scene's, one per project
    // workgroup) and `tile_count` tiles.
    void ensure(std::uint32_t clusters, std::uint32_t tile_count);
    // Room for `splats` projected splats and for `pairs` tile-splat pairs of `words`-word keys (at most
    // the sort's limit), which the frame reads back after its scan: grown with room to spare (a quarter
    // for the splats, a sixteenth for the keys), and made anew smaller when three quarters would do, so
    // that they follow what the view draws. Contents are not kept.
    // In strips (SplatPassSettings::frame_memory_limit) the room to spare stops at `most` (never below
    // the need).
    void ensure_splats(std::uint32_t splats, std::uint32_t most = ~0u);
    void ensure_keys(std::uint32_t pairs, std::uint32_t words, std::uint32_t most = ~0u);
    // The counters, the budget's histograms (with a budget), the tile ranges and the clusters' pair
    // counts at zero, and the cluster list empty, before step 1 fills them.
    void clear(bool with_budget);
    // Before a selection of a strip after the first: the frame's counters as the strips drawn so far left
    // them (kept at the strip's first selection, put back at any other), with no splats reserved, and
    // the tile ranges, the clusters' pair counts and the cluster list cleared.
    void clear_strip();
    void strip_drawn() { counters_kept_ = false; }  // the next strip's first selection keeps them anew
    // The per-frame buffers that grow with the scene and the view.
    std::uint64_t bytes() const;

private:
    void clear_selection();  // the tile ranges, the clusters' pair counts and the cluster list
    bool counters_kept_ = false;
};

// The raster's output below render scale 1: value, d/dx, d/dy, d²/dxdy (RGBA32F) and the front depths
// (RGBA32F: front, median and expected depth), kept while the raster size stays the same.
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

// With SplatPassSettings::splat_depth: the splats' own depths at the output size (RG32F: median,
// expected), kept while the output size stays the same.
struct SplatDepthImage {
    int width = 0, height = 0;
    engine::gl::Texture image{engine::gl::NoCreate};

    void ensure(int w, int h);
    std::uint64_t bytes() const;
    SplatDepth read() const;  // blocking; empty when there is none
};

}  // namespace splat_lod
