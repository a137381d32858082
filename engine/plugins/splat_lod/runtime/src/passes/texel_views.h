#pragma once
// How the splat steps read their inputs (RasterFetch): from storage buffers, or on CPU drivers through
// buffer-texture views with texel fetches (docs/algorithms.md §1, "Raster"). The views are re-pointed
// every frame, since buffers are reallocated when they grow.
#include <cstdint>
#include <optional>

#include "engine/gl/compute_step.h"
#include "engine/gl/objects.h"
#include "gpu/gpu_scene.h"
#include "passes/frame_buffers.h"
#include "splat_lod/splat_renderer.h"

namespace splat_lod {

class TexelViews {
public:
    // `wanted` for this driver and these sizes: texel fetches need buffer textures as long as every
    // buffer read through them (the scene's Gaussians, SH and instances, the projected splats at 3
    // texels each, the keys); `in_use` is last frame's choice (a fall-back is logged once).
    RasterFetch resolve(RasterFetch wanted, std::uint32_t splat_capacity, std::uint32_t key_capacity,
                        const gpu::GpuScene& scene, RasterFetch in_use);

    // The views each step reads, each followed by a texture-fetch barrier. Step 1b: the Gaussians, SH
    // and instances (unsigned words: bit-exact); step 3: the projected splats as words; step 5: the sorted keys; step
    // 6: the projected splats and the sorted values.
    void bind_project(const gpu::GpuScene& scene);
    void bind_bin(const FrameBuffers& buffers);
    void bind_ranges(const FrameBuffers& buffers, bool one_word_keys);
    void bind_raster(const FrameBuffers& buffers);

private:
    std::optional<engine::gl::DriverLimits> driver_;  // asked once
    engine::gl::Texture projected_texels_{engine::gl::NoCreate}, value_texels_{engine::gl::NoCreate};
    engine::gl::Texture gaussian_texels_{engine::gl::NoCreate}, sh_texels_{engine::gl::NoCreate},
        instance_texels_{engine::gl::NoCreate}, codec_texels_{engine::gl::NoCreate},
        projected_words_{engine::gl::NoCreate}, key_texels_{engine::gl::NoCreate};
};

}  // namespace splat_lod
