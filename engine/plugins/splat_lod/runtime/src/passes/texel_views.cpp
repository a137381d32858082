// The steps' texel views of their input buffers (texel_views.h).
#include "passes/texel_views.h"

#include <algorithm>
#include <string>

#include "engine/core/log.h"
#include "engine/gl/buffer_texture.h"
#include "gpu/gpu_layout.h"

namespace splat_lod {

RasterFetch TexelViews::resolve(RasterFetch wanted, std::uint32_t splat_capacity, std::uint32_t key_capacity,
                                const gpu::GpuScene& scene, RasterFetch in_use) {
    if (!driver_) driver_ = engine::gl::driver_limits();
    RasterFetch fetch = wanted;
    if (fetch == RasterFetch::automatic) fetch = driver_->cpu_rasteriser ? RasterFetch::texel : RasterFetch::shared;
    // Compact records and SH are read a word a texel, full ones a vec4 and a coefficient (12 bytes).
    const bool compact = scene.storage() == GpuStorage::compact;
    const std::uint64_t needed =
        std::max({std::uint64_t(splat_capacity) * 3, std::uint64_t(key_capacity),
                  std::uint64_t(scene.gaussians().size() / (compact ? 4 : 16)),
                  std::uint64_t(scene.sh().size() / (compact ? 4 : 12)), std::uint64_t(scene.instances().size() / 16)});
    const auto limit = static_cast<std::uint64_t>(driver_->max_texture_buffer_texels);
    if (fetch == RasterFetch::texel && needed > limit) {
        if (in_use != RasterFetch::shared)
            engine::log_warning("splat_lod: " + std::to_string(needed) +
                                " texels exceed the driver's buffer textures (" + std::to_string(limit) +
                                "); the passes read storage buffers and the raster stages splats in shared memory");
        fetch = RasterFetch::shared;
    }
    return fetch;
}

void TexelViews::bind_project(const gpu::GpuScene& scene) {
    const bool compact = scene.storage() == GpuStorage::compact;
    engine::gl::bind_buffer_texture(gaussian_texels_, "splat gaussian texels", compact ? GL_R32UI : GL_RGBA32UI,
                                    scene.gaussians(), SPLAT_TEXTURE_GAUSSIANS);
    engine::gl::bind_buffer_texture(sh_texels_, "splat sh texels", compact ? GL_R32UI : GL_RGB32UI, scene.sh(),
                                    SPLAT_TEXTURE_SH);
    if (compact)
        engine::gl::bind_buffer_texture(codec_texels_, "splat page codec texels", GL_RGBA32UI, scene.page_codecs(),
                                        SPLAT_TEXTURE_PAGE_CODECS);
    engine::gl::bind_buffer_texture(instance_texels_, "splat instance texels", GL_RGBA32UI, scene.instances(),
                                    SPLAT_TEXTURE_INSTANCES);
    engine::gl::memory_barrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // uploaded as buffers, read as texels
}

void TexelViews::bind_bin(const FrameBuffers& buffers) {
    engine::gl::bind_buffer_texture(projected_words_, "splat projected words", GL_RGBA32UI, buffers.projected,
                                    SPLAT_TEXTURE_PROJECTED_WORDS);
    engine::gl::memory_barrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // written through storage buffers, read as texels
}

void TexelViews::bind_ranges(const FrameBuffers& buffers, bool one_word_keys) {
    engine::gl::bind_buffer_texture(key_texels_, "splat sorted key texels", one_word_keys ? GL_R32UI : GL_RG32UI,
                                    buffers.keys, SPLAT_TEXTURE_SORTED_KEYS);
    engine::gl::memory_barrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // sorted through storage buffers, read as texels
}

void TexelViews::bind_raster(const FrameBuffers& buffers) {
    engine::gl::bind_buffer_texture(projected_texels_, "splat projected texels", GL_RGBA32F, buffers.projected,
                                    SPLAT_TEXTURE_PROJECTED);
    engine::gl::bind_buffer_texture(value_texels_, "splat value texels", GL_R32UI, buffers.values,
                                    SPLAT_TEXTURE_VALUES);
    engine::gl::memory_barrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // written through storage buffers, read as texels
}

}  // namespace splat_lod
