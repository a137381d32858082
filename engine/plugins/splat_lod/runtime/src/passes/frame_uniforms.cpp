// The raster size and the frame's uniforms (frame_uniforms.h).
#include "passes/frame_uniforms.h"

#include <bit>
#include <cmath>
#include <string>

#include "engine/core/error.h"
#include "engine/gl/compute_step.h"
#include "engine/render/render_target.h"
#include "splat_lod/core/upscale.h"

namespace splat_lod {

RasterSize raster_size(const SplatPassSettings& settings, const plugin_msgs::LodSettings& lod, int output_width,
                       int output_height) {
    if (const std::string error = lod.validate(); !error.empty()) engine::fail("splat_lod: " + error);
    const float s = lod.render_scale;
    RasterSize r;
    r.scale = s;
    r.upscaled = s < 1.0f;
    r.width = r.upscaled ? upscale::low_res_size(output_width, s) : output_width;
    r.height = r.upscaled ? upscale::low_res_size(output_height, s) : output_height;
    r.tile_size = r.upscaled ? settings.low_res_tile_size : settings.tile_size;
    if (r.tile_size != 4 && r.tile_size != 8 && r.tile_size != 16)
        engine::fail("splat_lod: raster tile size must be 4, 8 or 16, got " + std::to_string(r.tile_size));
    r.tiles_x = engine::gl::groups_for(static_cast<std::uint32_t>(r.width), r.tile_size);
    r.tiles_y = engine::gl::groups_for(static_cast<std::uint32_t>(r.height), r.tile_size);
    // One-word keys hold the tile (bit_width(tile_count) bits: tile_count itself is step 3's filler)
    // above the quantised depth, when that leaves the depth at least 16 bits.
    const auto tile_bits = static_cast<std::uint32_t>(std::bit_width(r.tile_count()));
    r.key_depth_bits = settings.compact_sort_keys && tile_bits <= 16 ? 32 - tile_bits : 0;
    return r;
}

gpu::FrameUniforms frame_uniforms(const SplatPassSettings& settings, const plugin_msgs::LodSettings& lod,
                                  const engine::FrameContext& frame, const RasterSize& raster,
                                  const gpu::GpuScene& scene) {
    const engine::CameraView& camera = frame.camera;
    // The raster's pixel coordinates are the output's times s (splat_lod/core/upscale.h); the Jacobian's
    // clamp stays the output camera's, so both resolutions clamp the same Gaussians.
    const float s = raster.scale;
    const float f = camera.focal_length() * s;
    const float tan_y = std::tan(0.5f * camera.fov_y);
    const float tan_x = tan_y * camera.aspect();  // the whole image's, also for a tile of it (camera.h)
    gpu::FrameUniforms u{};
    u.view = camera.view;
    u.camera_position = camera.position;
    u.separate_selection = camera.selection_view ? 1u : 0u;
    u.selection_view = camera.selection_view.value_or(camera.view);
    u.znear = settings.znear;
    u.focal = glm::vec2(f, f);
    u.principal = camera.principal_point() * s;
    u.raster_size = glm::vec2(raster.width, raster.height);
    u.jacobian_clamp = glm::vec2(1.3f * tan_x, 1.3f * tan_y);
    // Resolution-consistent dilation (docs/algorithms.md §5): 0.3 output px² is 0.3·s² raster px².
    u.dilation = settings.dilation * (settings.scaled_dilation ? s * s : 1.0f);
    u.mip_filter = lod.mip_filter ? 1u : 0u;
    u.cluster_skipping = settings.cluster_skipping ? 1u : 0u;
    u.frustum_culling = settings.frustum_culling ? 1u : 0u;
    u.gaussian_count = scene.gaussian_count();
    u.sh_stride = scene.sh_stride();
    u.sh_storage_degree = static_cast<std::uint32_t>(scene.sh_degree());
    u.instance_count = scene.instance_count();
    u.tiles = glm::uvec2(raster.tiles_x, raster.tiles_y);
    u.tile_count = raster.tile_count();
    u.tile_size = raster.tile_size;
    u.strip_first_row = 0;  // every row; SplatPass sets a strip's
    u.strip_end_row = raster.tiles_y;
    gpu::write_lod_rule(u, lod.rule);
    u.coverage_scale = 1.0f / s;
    u.coarsest_level = scene.coarsest_level();
    u.level_colouring = lod.level_colouring ? 1u : 0u;
    u.output_size = glm::vec2(frame.target.width(), frame.target.height());
    u.render_scale = s;
    u.inverse_render_scale = 1.0f / s;
    u.splat_budget = lod.splat_budget;
    u.exact_tiles = settings.exact_tiles ? 1u : 0u;
    u.key_depth_bits = raster.key_depth_bits;
    return u;
}

}  // namespace splat_lod
