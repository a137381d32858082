#pragma once
// The splat frame: every splat component of the scene drawn as one depth-sorted set, in compute
// passes (numbered in SplatPass::execute), composited over the mesh pass's colour by its view depth.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "splat_lod/msgs/lod_settings.h"
#include "splat_lod/msgs/splat_statistics.h"

#include "engine/core/error.h"
#include "engine/gl/objects.h"
#include "engine/render/render_pass.h"
#include "gpu/gpu_scene.h"
#include "splat_lod/core/lod_selection.h"
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

    SplatPassSettings settings;
    // Takes a LodSettings message whole (published on the bus): settings.lod is that message.
    void apply(const plugin_msgs::LodSettings& lod);

    // The newest statistics read back so far (also published on the bus).
    const std::optional<plugin_msgs::SplatStatistics>& latest_statistics() const { return latest_; }
    // Blocks until the statistics of every frame drawn so far are read; for tools and tests.
    void wait_for_statistics(engine::MessageBus& bus);
    std::uint32_t key_capacity() const { return key_capacity_; }
    RasterFetch raster_fetch_in_use() const { return fetch_in_use_; }
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
    // low-resolution size of splat_lod/core/upscale.h.
    struct RasterSize {
        float scale = 1.0f;
        bool upscaled = false;
        int width = 0, height = 0;
        std::uint32_t tile_size = SPLAT_TILE_SIZE;
        std::uint32_t tiles_x = 0, tiles_y = 0;
        std::uint32_t key_depth_bits = 0;  // FrameUniforms::key_depth_bits
    };
    RasterSize raster_size(const engine::FrameContext& frame) const;
    void ensure_frame_buffers(std::uint32_t gaussians, std::uint32_t tile_count);
    void ensure_low_res_images(int width, int height);
    std::uint64_t low_res_bytes() const;
    void upload_frame_uniforms(const engine::FrameContext& frame, const RasterSize& raster);
    void bind_all(const engine::FrameContext& frame);
    void clear_frame_buffers();
    void record_selection(engine::FrameContext& frame, std::uint32_t gaussians);
    void record_sort(engine::FrameContext& frame, std::uint32_t gaussians, const RasterSize& raster);
    void record_raster(engine::FrameContext& frame, const RasterSize& raster);
    RasterFetch resolve_fetch(std::uint32_t gaussians);
    const engine::gl::Program& texel_program(engine::FrameContext& frame, const char* file, void (SplatPass::*bind)());
    void bind_project_texels();
    void bind_bin_texels();
    void bind_ranges_texels();
    void bind_raster_texels();
    void record_statistics(engine::FrameContext& frame);
    void collect_statistics(engine::MessageBus& bus, bool wait);

    gpu::GpuScene scene_;
    std::unique_ptr<engine::gl::PrefixScan> scan_;
    std::unique_ptr<engine::gl::RadixSort> sort_;
    std::uint32_t key_capacity_ = 0;
    std::uint32_t pending_growth_ = 0;  // keys a past frame needed beyond the capacity
    engine::gl::Buffer uniforms_{engine::gl::NoCreate}, projected_{engine::gl::NoCreate},
        tile_counts_{engine::gl::NoCreate}, keys_{engine::gl::NoCreate}, values_{engine::gl::NoCreate},
        tile_ranges_{engine::gl::NoCreate}, counters_{engine::gl::NoCreate}, args_{engine::gl::NoCreate},
        count_{engine::gl::NoCreate}, cluster_list_{engine::gl::NoCreate}, budget_{engine::gl::NoCreate};
    struct LowResImages {
        int width = 0, height = 0;
        std::array<engine::gl::Texture, 4> images{
            engine::gl::Texture(engine::gl::NoCreate), engine::gl::Texture(engine::gl::NoCreate),
            engine::gl::Texture(engine::gl::NoCreate), engine::gl::Texture(engine::gl::NoCreate)};
        engine::gl::Texture front{engine::gl::NoCreate};
    } low_;
    std::array<Readback, 4> readbacks_;
    std::uint64_t frames_ = 0;
    RasterFetch fetch_in_use_ = RasterFetch::automatic;
    std::optional<bool> cpu_driver_;  // the GL renderer is a CPU rasteriser (asked once)
    GLint max_texels_ = 0;            // GL_MAX_TEXTURE_BUFFER_SIZE (asked with cpu_driver_)
    engine::gl::Texture projected_texels_{engine::gl::NoCreate}, value_texels_{engine::gl::NoCreate};
    engine::gl::Texture gaussian_texels_{engine::gl::NoCreate}, sh_texels_{engine::gl::NoCreate},
        instance_texels_{engine::gl::NoCreate}, projected_words_{engine::gl::NoCreate},
        key_offset_texels_{engine::gl::NoCreate}, key_texels_{engine::gl::NoCreate};
    std::optional<plugin_msgs::SplatStatistics> latest_;
};

// The plugin's pass in a running engine (nullptr when the plugin is not started).
SplatPass* find_splat_pass(engine::Renderer& renderer);

}  // namespace splat_lod
