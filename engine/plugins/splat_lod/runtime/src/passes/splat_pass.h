#pragma once
// The splat frame: every splat component of the scene drawn as one depth-sorted set, in compute
// steps (frame_steps.h), composited over the mesh pass's colour by its view depth. The pass owns what
// lives across frames (the GPU scene, the frame's buffers, the texel views, the statistics' readbacks)
// and runs the steps in order; it makes no GL call of its own.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "splat_lod/msgs/lod_settings.h"
#include "splat_lod/msgs/splat_statistics.h"

#include "engine/render/render_pass.h"
#include "gpu/gpu_scene.h"
#include "passes/frame_buffers.h"
#include "passes/frame_picks.h"
#include "passes/frame_statistics.h"
#include "passes/frame_steps.h"
#include "passes/texel_views.h"
#include "splat_lod/core/upscale.h"
#include "splat_lod/splat_renderer.h"

namespace engine::gl {
class PrefixScan;
class RadixSort;
}  // namespace engine::gl

namespace splat_lod {

class SplatPass : public engine::RenderPass {
public:
    SplatPass();
    ~SplatPass() override;
    std::string name() const override { return "splat"; }
    int order() const override { return engine::pass_order::plugin; }
    void execute(engine::FrameContext& frame) override;
    // The splats under a picked pixel (frame_picks.h), a frame or more after it was drawn.
    engine::PickResult pick_answer(std::uint64_t ticket, bool wait) override { return picks_.answer(ticket, wait); }
    // Pick readbacks in flight (a test's count: answering never waits on them unless asked to).
    std::size_t picks_in_flight() const { return picks_.in_flight(); }

    SplatPassSettings settings;
    // Takes a LodSettings message whole, as the bus delivers it (the only way LOD settings arrive).
    void apply(const plugin_msgs::LodSettings& lod);
    const plugin_msgs::LodSettings& lod() const { return lod_; }

    // The newest statistics read back so far (also published on the bus).
    const std::optional<plugin_msgs::SplatStatistics>& latest_statistics() const { return statistics_.latest(); }
    // Blocks until the statistics of every frame drawn so far are read; for tools and tests.
    void wait_for_statistics(engine::MessageBus& bus);
    std::uint32_t key_capacity() const { return buffers_.key_capacity; }
    // GPU bytes of the per-frame buffers, the scan's and the sort's own, and the low-resolution images.
    std::uint64_t frame_bytes() const;
    // Of those, the buffers SplatPassSettings::frame_memory_limit bounds: projected splats, keys, the sort's.
    std::uint64_t view_bytes() const;
    // Splats the latest frame projected (the dense array's need) and the tile-splat pairs it sorted.
    FrameCounts last_frame_counts() const { return last_counts_; }
    RasterFetch raster_fetch_in_use() const { return fetch_in_use_; }
    // The resident Gaussians (which clouds, where, what the last frame uploaded); for tools and tests.
    const gpu::GpuScene& scene() const { return scene_; }
    // For reserve(): a streamed world sizes the scene for its memory budget up front (sample_game).
    gpu::GpuScene& scene() { return scene_; }
    // The last frame's low-resolution splat image with its derivatives (rows top first) and its
    // front depths, read back blocking; empty at render scale 1. For tools and tests.
    upscale::GradientImage read_low_res_image() const { return low_.read_image(); }
    std::vector<float> read_low_res_front_depth() const { return low_.read_front_depth(); }
    // The last frame's splat depths when settings.splat_depth was on (SplatDepth), read back blocking.
    SplatDepth read_splat_depth() const { return depth_.read(); }

private:
    FrameCounts draw_strips(FrameSteps& steps, gpu::FrameUniforms& uniforms, const StripRoom& room, bool picked);
    void draw_strip(FrameSteps& steps, gpu::FrameUniforms& uniforms, const FrameCounts& strip, const StripRoom& room,
                    bool picked);

    plugin_msgs::LodSettings lod_;
    gpu::GpuScene scene_;
    FrameBuffers buffers_;
    LowResImages low_;
    SplatDepthImage depth_;
    TexelViews texels_;
    FrameStatistics statistics_;
    FramePicks picks_;
    std::unique_ptr<engine::gl::PrefixScan> scan_;
    std::unique_ptr<engine::gl::RadixSort> sort_;
    RasterFetch fetch_in_use_ = RasterFetch::automatic;
    FrameCounts last_counts_;
    std::vector<DrawnStrip> last_strips_;  // the strips of the last frame, which plan the next
};

// The plugin's pass in a running engine (nullptr when the plugin is not started).
SplatPass* find_splat_pass(engine::Renderer& renderer);

}  // namespace splat_lod
