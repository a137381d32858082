#pragma once
// The splat frame: every splat component of the scene drawn as one depth-sorted set, in compute
// passes (ARCHITECTURE "Frame"), composited over the mesh pass's colour by its view depth.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include <plugin_msgs/splat_statistics.h>

#include "engine/gl/objects.h"
#include "engine/render/render_pass.h"
#include "gpu/gpu_scene.h"
#include "splat_lod/lod_selection.h"

namespace splat_lod {

namespace gpu {
class PrefixScan;
class RadixSort;
}  // namespace gpu

struct SplatPassSettings {
    float znear = 0.2f;       // ALGORITHMS §1
    float dilation = 0.3f;    // the EWA low-pass, in px²
    bool mip_filter = false;  // the optional 2D mip filter
    LodRule lod;              // selection by pixel coverage (coarsest_level is set from the scene)
    bool level_colouring = false;  // debug view: tint each Gaussian by its LOD level
    // Skip whole project workgroups whose Gaussians are all too small to be selected (exact: the
    // image and counts are the same either way; off only to measure what it saves).
    bool cluster_skipping = true;
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

private:
    struct Readback {
        engine::gl::Buffer buffer{engine::gl::NoCreate};
        engine::gl::Fence fence;
        std::uint64_t frame = 0;
        std::uint64_t resident_bytes = 0;
    };
    void ensure_frame_buffers(std::uint32_t gaussians, std::uint32_t tile_count);
    void upload_frame_uniforms(const engine::FrameContext& frame, std::uint32_t tiles_x, std::uint32_t tiles_y);
    void bind_all(const engine::FrameContext& frame);
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
        count_{engine::gl::NoCreate}, cluster_list_{engine::gl::NoCreate};
    std::array<Readback, 4> readbacks_;
    std::uint64_t frames_ = 0;
    std::optional<plugin_msgs::SplatStatistics> latest_;
};

}  // namespace splat_lod
