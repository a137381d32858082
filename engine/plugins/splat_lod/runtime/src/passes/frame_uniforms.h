#pragma once
// What a splat frame draws at (the raster's size, tiles and key layout) and the uniforms every step of
// it reads, from the pass's settings, the camera and the resident scene.
#include <cstdint>

#include "engine/render/render_pass.h"
#include "gpu/gpu_layout.h"
#include "gpu/gpu_scene.h"
#include "splat_lod/splat_renderer.h"

namespace splat_lod {

// The output size at render scale 1, else the low-resolution size of splat_lod/core/upscale.h.
struct RasterSize {
    float scale = 1.0f;
    bool upscaled = false;
    int width = 0, height = 0;
    std::uint32_t tile_size = SPLAT_TILE_SIZE;
    std::uint32_t tiles_x = 0, tiles_y = 0;
    std::uint32_t key_depth_bits = 0;  // FrameUniforms::key_depth_bits
    std::uint32_t tile_count() const { return tiles_x * tiles_y; }
};

// Throws engine::Error on invalid settings (set directly, not through the bus, which validates).
RasterSize raster_size(const SplatPassSettings& settings, const plugin_msgs::LodSettings& lod, int output_width,
                       int output_height);

// Everything but splat_capacity and key_capacity, which the frame sets as it sizes its buffers.
gpu::FrameUniforms frame_uniforms(const SplatPassSettings& settings, const plugin_msgs::LodSettings& lod,
                                  const engine::FrameContext& frame, const RasterSize& raster,
                                  const gpu::GpuScene& scene);

}  // namespace splat_lod
