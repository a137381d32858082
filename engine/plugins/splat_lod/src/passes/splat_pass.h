#pragma once
// The splat frame: every splat component of the scene drawn as one depth-sorted set, in compute
// passes (numbered in SplatPass::execute), composited over the mesh pass's colour by its view depth.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include <plugin_msgs/lod_settings.h>
#include <plugin_msgs/splat_statistics.h>

#include "engine/core/error.h"
#include "engine/gl/objects.h"
#include "engine/render/render_pass.h"
#include "gpu/gpu_scene.h"
#include "splat_lod/lod_selection.h"
#include "splat_lod/upscale.h"

namespace splat_lod {

namespace gpu {
class PrefixScan;
class RadixSort;
}  // namespace gpu

struct SplatPassSettings {
    float znear = 0.2f;       // docs/algorithms.md §1
    float dilation = 0.3f;    // the EWA low-pass, in px²
    bool mip_filter = false;  // the optional 2D mip filter
    LodRule lod;              // selection by pixel coverage (coarsest_level is set from the scene)
    bool level_colouring = false;  // debug view: tint each Gaussian by its LOD level
    // Skip whole project workgroups whose Gaussians are all too small to be selected (exact: the
    // image and counts are the same either way; off only to measure what it saves).
    bool cluster_skipping = true;
    // Drop whole clusters that the view frustum leaves out before per-Gaussian work (exact, like the
    // skipping; off only to measure what it saves and to test that the image does not change).
    bool frustum_culling = true;
    // At most this many Gaussians drawn per frame (0: no budget). When the selection would draw more,
    // the frame selects as if every coverage were β times smaller (S_T and the coverage ranges β times
    // larger: coarser levels), the smallest β in eighth-octave steps that fits, chosen on the GPU in
    // the same frame; if even β ≈ 3700 does not fit, the smallest of those Gaussians are dropped.
    std::uint32_t splat_budget = 0;
    // Gradient-aware upscaling (docs/algorithms.md §5): below 1 the splats are rasterised at this fraction
    // of the output size, with their analytic image derivatives, and brought to the output by
    // `upscaler` before compositing over the mesh pass. Outside (0, 1] execute() throws engine::Error.
    float render_scale = 1.0f;
    plugin_msgs::Upscaler upscaler = plugin_msgs::Upscaler::spline;
    // Resolution-consistent dilation: at render scale s the EWA low-pass is dilation·s² low-res px²,
    // the same blur as the native render (off only to measure the plain 0.3 px²).
    bool scaled_dilation = true;
    // Raster tile side in pixels (4, 8 or 16). The cost balances per-pixel list length (the splats
    // touching the tile) against tile-splat pairs to sort. Measured on llvmpipe, biker 960×540:
    // native 16 → 8 cut the raster 1024 → 646 ms but grew the sort 213 → 511 ms (same total); at
    // render scale 1/3, where splats are a third as wide, 16 → 8 cut the frame 726 → 409 ms.
    std::uint32_t tile_size = SPLAT_TILE_SIZE;
    std::uint32_t low_res_tile_size = 8;  // raster tile side below render scale 1 (8 or 16)
};

class SplatPass : public engine::RenderPass {
public:
    SplatPass();
    ~SplatPass() override;
    std::string name() const override { return "splat"; }
    int order() const override { return engine::pass_order::plugin; }
    void execute(engine::FrameContext& frame) override;

    SplatPassSettings settings;
    // Takes the mode, thresholds and mip filter of a LodSettings message (published on the bus).
    void apply(const plugin_msgs::LodSettings& lod);

    // The newest statistics read back so far (also published on the bus).
    const std::optional<plugin_msgs::SplatStatistics>& latest_statistics() const { return latest_; }
    // Blocks until the statistics of every frame drawn so far are read; for tools and tests.
    void wait_for_statistics(engine::MessageBus& bus);
    std::uint32_t key_capacity() const { return key_capacity_; }
    // The resident Gaussians (which clouds, where, what the last frame uploaded); for tools and tests.
    const gpu::GpuScene& scene() const { return scene_; }
    // For reserve(): a streamed world sizes the scene for its memory budget up front (sample_game).
    gpu::GpuScene& scene() { return scene_; }
    // The last frame's low-resolution splat image with its derivatives (rows top first) and its
    // front depths, read back blocking; empty at render scale 1. For tools and tests.
    upscale::GradientImage read_low_res_image() const;
    std::vector<float> read_low_res_front_depth() const;

private:
    struct Readback {
        engine::gl::Buffer buffer{engine::gl::NoCreate};
        engine::gl::Fence fence;
        std::uint64_t frame = 0;
        std::uint64_t resident_bytes = 0;
        std::uint64_t considered = 0;
        std::uint32_t splat_budget = 0;
        float size_threshold_px = 0.0f;
    };
    // What the tile raster draws this frame: the output size at render scale 1, else the
    // low-resolution size of splat_lod/upscale.h.
    struct RasterSize {
        float scale = 1.0f;
        bool upscaled = false;
        int width = 0, height = 0;
        std::uint32_t tile_size = SPLAT_TILE_SIZE;
        std::uint32_t tiles_x = 0, tiles_y = 0;
    };
    RasterSize raster_size(const engine::FrameContext& frame) const;
    void ensure_frame_buffers(std::uint32_t gaussians, std::uint32_t tile_count);
    void ensure_low_res_images(int width, int height);
    std::uint64_t low_res_bytes() const;
    void upload_frame_uniforms(const engine::FrameContext& frame, const RasterSize& raster);
    void bind_all(const engine::FrameContext& frame);
    void record_selection(engine::FrameContext& frame, std::uint32_t gaussians);
    void record_raster(engine::FrameContext& frame, const RasterSize& raster);
    void record_statistics(engine::FrameContext& frame);
    void collect_statistics(engine::MessageBus& bus, bool wait);

    gpu::GpuScene scene_;
    std::unique_ptr<gpu::PrefixScan> scan_;
    std::unique_ptr<gpu::RadixSort> sort_;
    std::uint32_t key_capacity_ = 0;
    std::uint32_t pending_growth_ = 0;  // keys a past frame needed beyond the capacity
    engine::gl::Buffer uniforms_{engine::gl::NoCreate}, projected_{engine::gl::NoCreate},
        tile_counts_{engine::gl::NoCreate}, keys_{engine::gl::NoCreate}, values_{engine::gl::NoCreate},
        tile_ranges_{engine::gl::NoCreate}, counters_{engine::gl::NoCreate}, args_{engine::gl::NoCreate},
        count_{engine::gl::NoCreate}, cluster_list_{engine::gl::NoCreate}, budget_{engine::gl::NoCreate};
    struct LowResImages {
        int width = 0, height = 0;
        std::array<engine::gl::Texture, 4> images{engine::gl::Texture(engine::gl::NoCreate), engine::gl::Texture(engine::gl::NoCreate),
                                                  engine::gl::Texture(engine::gl::NoCreate), engine::gl::Texture(engine::gl::NoCreate)};
        engine::gl::Texture front{engine::gl::NoCreate};
    } low_;
    std::array<Readback, 4> readbacks_;
    std::uint64_t frames_ = 0;
    std::optional<plugin_msgs::SplatStatistics> latest_;
};

}  // namespace splat_lod
