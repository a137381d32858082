#pragma once
// The steps of the splat frame, as data (engine/gl/compute_step.h), numbered as in SplatPass::execute:
//   1 selection   a: cull clusters outside the frustum, skip those too small for the view;
//                 b: cull + project + SH colour, tiles touched; under a splat budget c: choose β,
//                 d: keep what is selected at it                                  (selection_steps.cpp)
//   2–5 sort      scan of the clusters' pair counts; then, once the CPU has read the frame's splat and
//                 pair counts back and sized the buffers, bin into (depth, tile) keys, radix sort,
//                 tile ranges                                                      (sort_steps.cpp)
//   5½ picking    with pixels picked this frame: each one's tile walked as the raster will (raster_steps.cpp)
//   6–7 raster    per-tile front-to-back raster composited over the mesh pass; below render scale 1 at
//                 low resolution with derivatives, then the upscale to the output  (raster_steps.cpp)
// Every step binds the frame's whole set of resources (the sort and the scan bind their own between).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "engine/gl/prefix_scan.h"
#include "engine/gl/radix_sort.h"
#include "engine/gl/shader_library.h"
#include "engine/render/render_pass.h"
#include "gpu/gpu_scene.h"
#include "passes/frame_buffers.h"
#include "passes/frame_strips.h"
#include "passes/frame_uniforms.h"
#include "passes/texel_views.h"
#include "splat_lod/splat_renderer.h"

namespace splat_lod {

// What the steps of one frame read and write.
struct FrameSteps {
    engine::FrameContext& frame;
    const SplatPassSettings& settings;
    const plugin_msgs::LodSettings& lod;
    const RasterSize& raster;
    const gpu::GpuScene& scene;
    FrameBuffers& buffers;
    const LowResImages& low;
    const SplatDepthImage& depth;  // none unless SplatPassSettings::splat_depth
    TexelViews& texels;
    RasterFetch fetch;
    engine::gl::PrefixScan& scan;
    engine::gl::RadixSort& sort;

    // Binds the uniforms, the scene's and the frame's buffers, the target's colour and view depth, and
    // the low-resolution images and the splat depth image when there are any.
    void bind_all() const;
    // The defines of the steps that write the output's depth: SPLAT_DEPTH_IMAGE with a splat depth image.
    std::vector<std::string> depth_defines() const {
        return depth.width > 0 ? std::vector<std::string>{"SPLAT_DEPTH_IMAGE"} : std::vector<std::string>{};
    }
    // A program of the plugin's shaders, with `defines`.
    const engine::gl::Program& program(const char* file, const std::vector<std::string>& defines = {}) const;
    // A program that reads the scene's Gaussians (common_splat_storage.glsl): SPLAT_COMPACT_STORAGE
    // defined when the scene is compact.
    const engine::gl::Program& storage_program(const char* file, std::vector<std::string> defines = {}) const {
        if (scene.storage() == GpuStorage::compact) defines.emplace_back("SPLAT_COMPACT_STORAGE");
        return program(file, defines);
    }
    // The storage program that reads its inputs through texel views when `fetch` is texel (binding
    // them with `bind_views`, SPLAT_INPUT_TEXELS defined), else from storage buffers.
    template <typename BindViews>
    const engine::gl::Program& input_program(const char* file, BindViews&& bind_views,
                                             std::vector<std::string> defines = {}) const {
        if (fetch != RasterFetch::texel) return storage_program(file, std::move(defines));
        bind_views();
        defines.emplace_back("SPLAT_INPUT_TEXELS");
        return storage_program(file, std::move(defines));
    }
    // One-word sort keys (FrameUniforms::key_depth_bits > 0): the key buffer holds a uint per pair.
    bool one_word_keys() const { return raster.key_depth_bits > 0; }
    std::vector<std::string> key_defines() const {
        return one_word_keys() ? std::vector<std::string>{"SPLAT_ONE_WORD_KEYS"} : std::vector<std::string>{};
    }
};

// Storage writes visible to the next step's reads, its indirect dispatch and its uniforms.
inline constexpr GLbitfield kStepBarrier =
    GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT;
// Image writes visible to everything that reads the target or the images afterwards.
inline constexpr GLbitfield kImageBarrier = GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                                            GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT;

// What steps 1–2 found: the splats projected and the tile-splat pairs they need. For a frame (SplatPass),
// the sums over its strips and the strips drawn.
struct FrameCounts {
    std::uint32_t splats = 0;
    std::uint32_t pairs = 0;
    std::uint32_t selection_runs = 0;  // 1, or more when steps 1–2 ran again (the splats did not fit)
    bool fits = true;                  // within the strip's room (StripRoom)
    std::uint32_t strips = 1;
};

void record_selection(const FrameSteps& steps, std::uint32_t gaussians);
void record_scan(const FrameSteps& steps, std::uint32_t clusters);
// Steps 1–2 of the strip in `uniforms` (their splat capacity set here), then a blocking read of the two
// counts. When the splats did not fit, the array grows to hold them and steps 1–2 run again, unless they
// exceed the room and the strip can be split (more than one tile row): then it returns, not `fits`.
FrameCounts select_splats(const FrameSteps& steps, gpu::FrameUniforms& uniforms, std::uint32_t gaussians,
                          const StripRoom& room);
void record_sort(const FrameSteps& steps);
// 5½: answers the frame's picks (gpu::SplatPicks, uploaded) into the same buffer.
void record_picks(const FrameSteps& steps);
// 6: the raster of `tile_rows` rows of tiles from the strip's first (FrameUniforms::strip_first_row).
void record_raster(const FrameSteps& steps, std::uint32_t tile_rows);
// 7: below render scale 1, the upscale of the whole frame (after every strip's raster).
void record_upscale(const FrameSteps& steps);

}  // namespace splat_lod
