// Steps 5½ to 7 of the splat frame (frame_steps.h): picking, the tile raster and, below render scale 1, the
// upscale.
#include <string>
#include <vector>

#include "engine/gl/compute_step.h"
#include "engine/gl/gpu_timers.h"
#include "engine/render/render_target.h"
#include "passes/frame_steps.h"

namespace splat_lod {

void record_picks(const FrameSteps& steps) {
    engine::gl::GpuTimerScope t(steps.frame.timers, "splat.pick");
    steps.bind_all();
    engine::gl::run({.program = &steps.program("splat_pick.comp.glsl",
                                               {"RASTER_TILE_SIZE=" + std::to_string(steps.raster.tile_size)}),
                     .groups = {1, 1, 1},
                     .barrier = kStepBarrier});
}

void record_raster(const FrameSteps& steps, std::uint32_t tile_rows) {
    const RasterSize& raster = steps.raster;
    // 6. per-tile front-to-back raster, stopping at the mesh depth; composite C + T·mesh, or below render
    //    scale 1, C and A with their derivatives at low resolution
    engine::gl::GpuTimerScope t(steps.frame.timers, "splat.raster");
    steps.bind_all();
    std::vector<std::string> defines = steps.depth_defines();
    defines.push_back("RASTER_TILE_SIZE=" + std::to_string(raster.tile_size));
    if (raster.upscaled) defines.push_back("SPLAT_GRADIENTS");
    if (steps.fetch == RasterFetch::shared)
        defines.push_back("RASTER_FETCH_SHARED");
    else
        steps.texels.bind_raster(steps.buffers);
    engine::gl::run({.program = &steps.program("splat_tile_raster.comp.glsl", defines),
                     .groups = {raster.tiles_x, tile_rows, 1},
                     .barrier = kImageBarrier});
}

void record_upscale(const FrameSteps& steps) {
    using engine::gl::groups_for;
    if (!steps.raster.upscaled) return;
    {  // 7. upscale to the output and composite over the mesh pass
        engine::gl::GpuTimerScope t(steps.frame.timers, "splat.upscale");
        const auto method = static_cast<int>(steps.lod.upscaler);
        const auto width = static_cast<std::uint32_t>(steps.frame.target.width());
        const auto height = static_cast<std::uint32_t>(steps.frame.target.height());
        std::vector<std::string> defines = steps.depth_defines();
        defines.push_back("UPSCALE_METHOD=" + std::to_string(method));
        engine::gl::run({.program = &steps.program("splat_upscale.comp.glsl", defines),
                         .groups = {groups_for(width, SPLAT_UPSCALE_WORKGROUP_SIZE),
                                    groups_for(height, SPLAT_UPSCALE_WORKGROUP_SIZE), 1},
                         .barrier = kImageBarrier});
    }
}

}  // namespace splat_lod
