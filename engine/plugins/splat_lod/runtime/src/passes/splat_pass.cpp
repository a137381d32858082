#include "passes/splat_pass.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/core/message_bus.h"
#include "engine/gl/buffer_texture.h"
#include "engine/gl/gpu_timers.h"
#include "engine/gl/prefix_scan.h"
#include "engine/gl/radix_sort.h"
#include "engine/gl/shader_library.h"
#include "engine/render/render_target.h"
#include "engine/scene/scene.h"
#include "splat_lod/core/upscale.h"
#include "splat_lod/splat_component.h"

namespace splat_lod {
namespace {

using engine::gl::GpuTimerScope;
constexpr std::uint32_t initial_keys_per_gaussian = 4;
constexpr std::uint32_t minimum_key_capacity = 1u << 16;

std::uint32_t groups(std::uint32_t count, std::uint32_t size) {
    return (count + size - 1) / size;
}

const engine::gl::Program& program(engine::FrameContext& frame, const char* file) {
    return frame.shaders.program({std::string("splat_lod/") + file});
}

void barrier() {
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
}

}  // namespace

SplatPass::SplatPass() = default;

void SplatPass::apply(const plugin_msgs::LodSettings& lod) {
    settings.lod = lod;
}
SplatPass::~SplatPass() = default;

void SplatPass::ensure_frame_buffers(std::uint32_t gaussians, std::uint32_t tile_count) {
    using gpu::ProjectedSplat;
    if (!uniforms_) {
        uniforms_ = engine::gl::Buffer("splat frame uniforms");
        uniforms_.storage(sizeof(gpu::FrameUniforms));
        counters_ = engine::gl::Buffer("splat frame counters");
        counters_.storage(sizeof(gpu::FrameCounters));
        args_ = engine::gl::Buffer("splat dispatch args");
        args_.storage(sizeof(glm::uvec4));
        count_ = engine::gl::Buffer("splat gaussian count");
        count_.storage(sizeof(std::uint32_t));
        budget_ = engine::gl::Buffer("splat budget");
        budget_.storage(sizeof(gpu::SplatBudgetState));
        for (auto& r : readbacks_) {
            r.buffer = engine::gl::Buffer("splat counters readback");
            r.buffer.storage(sizeof(gpu::FrameCounters), nullptr, GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
        }
    }
    projected_.ensure_size(std::size_t(gaussians) * sizeof(ProjectedSplat), "splat projected");
    cluster_list_.ensure_size(
        sizeof(glm::uvec4) + std::size_t(groups(gaussians, SPLAT_PROJECT_WORKGROUP_SIZE)) * sizeof(std::uint32_t),
        "splat cluster list");
    tile_counts_.ensure_size((std::size_t(gaussians) + 1) * sizeof(std::uint32_t), "splat tile counts");
    tile_ranges_.ensure_size(std::size_t(tile_count) * sizeof(glm::uvec2), "splat tile ranges");
    const std::uint32_t wanted = std::max({key_capacity_, minimum_key_capacity, gaussians * initial_keys_per_gaussian,
                                           pending_growth_ + pending_growth_ / 4});
    const std::uint32_t capacity = std::min(wanted, engine::gl::RadixSort::max_sort_count());
    if (capacity != key_capacity_) {
        keys_.ensure_size(std::size_t(capacity) * sizeof(glm::uvec2), "splat tile keys");
        values_.ensure_size(std::size_t(capacity) * sizeof(std::uint32_t), "splat tile values");
        key_capacity_ = capacity;
    }
    pending_growth_ = 0;
}

void SplatPass::upload_frame_uniforms(const engine::FrameContext& frame, const RasterSize& raster) {
    const engine::CameraView& camera = frame.camera;
    // The raster's pixel coordinates are the output's times s (splat_lod/core/upscale.h); the Jacobian's
    // clamp stays the output camera's, so both resolutions clamp the same Gaussians.
    const float s = raster.scale;
    const float f = camera.focal_length() * s;
    const glm::vec2 c = camera.principal_point() * s;
    const float tan_y = std::tan(0.5f * camera.fov_y);
    const float tan_x = tan_y * camera.aspect();  // the whole image's, also for a tile of it (camera.h)
    gpu::FrameUniforms u{};
    u.view = camera.view;
    u.camera_position = camera.position;
    u.znear = settings.znear;
    u.focal = glm::vec2(f, f);
    u.principal = c;
    u.raster_size = glm::vec2(raster.width, raster.height);
    u.jacobian_clamp = glm::vec2(1.3f * tan_x, 1.3f * tan_y);
    // Resolution-consistent dilation (docs/algorithms.md §5): 0.3 output px² is 0.3·s² raster px².
    u.dilation = settings.dilation * (settings.scaled_dilation ? s * s : 1.0f);
    u.mip_filter = settings.lod.mip_filter ? 1u : 0u;
    u.cluster_skipping = settings.cluster_skipping ? 1u : 0u;
    u.frustum_culling = settings.frustum_culling ? 1u : 0u;
    u.gaussian_count = scene_.gaussian_count();
    u.sh_stride = scene_.sh_stride();
    u.key_capacity = key_capacity_;
    u.instance_count = scene_.instance_count();
    u.tiles = glm::uvec2(raster.tiles_x, raster.tiles_y);
    u.tile_count = raster.tiles_x * raster.tiles_y;
    u.tile_size = raster.tile_size;
    gpu::write_lod_rule(u, settings.lod.rule);
    u.coverage_scale = 1.0f / s;
    u.coarsest_level = scene_.coarsest_level();
    u.level_colouring = settings.lod.level_colouring ? 1u : 0u;
    u.output_size = glm::vec2(frame.target.width(), frame.target.height());
    u.render_scale = s;
    u.inverse_render_scale = 1.0f / s;
    u.splat_budget = settings.lod.splat_budget;
    u.exact_tiles = settings.exact_tiles ? 1u : 0u;
    u.key_depth_bits = raster.key_depth_bits;
    uniforms_.upload(0, sizeof(u), &u);
    const std::uint32_t count = scene_.gaussian_count();
    count_.upload(0, sizeof(count), &count);
}

SplatPass::RasterSize SplatPass::raster_size(const engine::FrameContext& frame) const {
    // Settings set directly (not through the bus, which validates) are checked here: an error, not garbage.
    if (const std::string error = settings.lod.validate(); !error.empty()) engine::fail("splat_lod: " + error);
    const float s = settings.lod.render_scale;
    RasterSize r;
    r.scale = s;
    r.upscaled = s < 1.0f;
    r.width = r.upscaled ? upscale::low_res_size(frame.target.width(), s) : frame.target.width();
    r.height = r.upscaled ? upscale::low_res_size(frame.target.height(), s) : frame.target.height();
    r.tile_size = r.upscaled ? settings.low_res_tile_size : settings.tile_size;
    if (r.tile_size != 4 && r.tile_size != 8 && r.tile_size != 16)
        engine::fail("splat_lod: raster tile size must be 4, 8 or 16, got " + std::to_string(r.tile_size));
    r.tiles_x = groups(static_cast<std::uint32_t>(r.width), r.tile_size);
    r.tiles_y = groups(static_cast<std::uint32_t>(r.height), r.tile_size);
    // One-word keys hold the tile (bit_width(tile_count) bits: tile_count itself is step 3's filler)
    // above the quantised depth, when that leaves the depth at least 16 bits.
    const auto tile_bits = static_cast<std::uint32_t>(std::bit_width(r.tiles_x * r.tiles_y));
    r.key_depth_bits = settings.compact_sort_keys && tile_bits <= 16 ? 32 - tile_bits : 0;
    return r;
}

// The low-resolution images of the upscaled path, kept while the raster size stays the same.
void SplatPass::ensure_low_res_images(int width, int height) {
    if (low_.width == width && low_.height == height) return;
    const char* labels[] = {"splat low-res value", "splat low-res dx", "splat low-res dy", "splat low-res dxy"};
    for (int k = 0; k < 4; ++k) {
        low_.images[k] = engine::gl::Texture(GL_TEXTURE_2D, labels[k]);
        glTextureStorage2D(low_.images[k].id(), 1, GL_RGBA32F, width, height);
    }
    low_.front = engine::gl::Texture(GL_TEXTURE_2D, "splat low-res front depth");
    glTextureStorage2D(low_.front.id(), 1, GL_R32F, width, height);
    low_.width = width;
    low_.height = height;
}

// The sort and the scan bind their own buffers; every pass of ours binds the whole set again.
void SplatPass::bind_all(const engine::FrameContext& frame) {
    glBindBufferBase(GL_UNIFORM_BUFFER, SPLAT_UNIFORM_FRAME, uniforms_.id());
    const std::pair<GLuint, GLuint> storage[] = {{SPLAT_BINDING_GAUSSIANS, scene_.gaussians().id()},
                                                 {SPLAT_BINDING_SH, scene_.sh().id()},
                                                 {SPLAT_BINDING_INSTANCES, scene_.instances().id()},
                                                 {SPLAT_BINDING_PROJECTED, projected_.id()},
                                                 {SPLAT_BINDING_CLUSTERS, scene_.clusters().id()},
                                                 {SPLAT_BINDING_CLUSTER_LIST, cluster_list_.id()},
                                                 {SPLAT_BINDING_TILE_COUNTS, tile_counts_.id()},
                                                 {SPLAT_BINDING_KEYS, keys_.id()},
                                                 {SPLAT_BINDING_VALUES, values_.id()},
                                                 {SPLAT_BINDING_TILE_RANGES, tile_ranges_.id()},
                                                 {SPLAT_BINDING_STATS, counters_.id()},
                                                 {SPLAT_BINDING_ARGS, args_.id()},
                                                 {SPLAT_BINDING_BUDGET, budget_.id()}};
    for (const auto& [binding, buffer] : storage) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer);
    glBindImageTexture(SPLAT_IMAGE_COLOR, frame.target.color().id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
    glBindTextureUnit(SPLAT_TEXTURE_VIEW_DEPTH, frame.target.view_depth().id());
    if (low_.width > 0) {
        for (int k = 0; k < 4; ++k)
            glBindImageTexture(SPLAT_IMAGE_LOW_VALUE + k, low_.images[k].id(), 0, GL_FALSE, 0, GL_READ_WRITE,
                               GL_RGBA32F);
        glBindImageTexture(SPLAT_IMAGE_LOW_FRONT, low_.front.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    }
}

// A pass's program: with texel fetches its inputs' views bound (`bind`) and SPLAT_INPUT_TEXELS defined,
// else the storage-buffer variant.
const engine::gl::Program& SplatPass::texel_program(engine::FrameContext& frame, const char* file,
                                                    void (SplatPass::*bind)()) {
    std::vector<std::string> defines;
    if (fetch_in_use_ == RasterFetch::texel) {
        (this->*bind)();
        defines.push_back("SPLAT_INPUT_TEXELS");
    }
    return frame.shaders.program({std::string("splat_lod/") + file}, defines);
}

// Step 1 (numbered as in execute): a: cull clusters outside the frustum, skip those too small for
// the view; b: cull + project + SH colour, tiles touched; under a splat budget c: choose β, d: keep
// what is selected at it.
void SplatPass::record_selection(engine::FrameContext& frame, std::uint32_t n) {
    GpuTimerScope t(frame.timers, "splat.project");
    bind_all(frame);
    glUseProgram(program(frame, "splat_clusters.comp.glsl").id());
    glDispatchCompute(groups(groups(n, SPLAT_PROJECT_WORKGROUP_SIZE), SPLAT_CLUSTER_WORKGROUP_SIZE), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    glUseProgram(texel_program(frame, "splat_project.comp.glsl", &SplatPass::bind_project_texels).id());
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, cluster_list_.id());
    glDispatchComputeIndirect(0);
    barrier();
    if (settings.lod.splat_budget > 0) {
        glUseProgram(program(frame, "splat_budget.comp.glsl").id());
        glDispatchCompute(1, 1, 1);
        barrier();
        glUseProgram(program(frame, "splat_budget_trim.comp.glsl").id());
        glDispatchComputeIndirect(0);
        barrier();
    }
}

// settings.raster_fetch for this driver and these sizes: texel fetches need buffer textures as long
// as every buffer read through them (the scene's Gaussians, SH and instances, the projected splats at
// 4 texels each, the keys).
RasterFetch SplatPass::resolve_fetch(std::uint32_t gaussians) {
    if (!cpu_driver_) {  // the driver's name and limit, asked once
        const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        const std::string name = renderer != nullptr ? renderer : "";
        cpu_driver_ = name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos;
        glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels_);
    }
    RasterFetch fetch = settings.raster_fetch;
    if (fetch == RasterFetch::automatic) fetch = *cpu_driver_ ? RasterFetch::texel : RasterFetch::shared;
    const std::uint64_t needed = std::max(
        {std::uint64_t(gaussians) * 4, std::uint64_t(key_capacity_), std::uint64_t(scene_.gaussians().size() / 16),
         std::uint64_t(scene_.sh().size() / 12), std::uint64_t(scene_.instances().size() / 16)});
    if (fetch == RasterFetch::texel && needed > static_cast<std::uint64_t>(max_texels_)) {
        if (fetch_in_use_ != RasterFetch::shared)
            engine::log_warning("splat_lod: " + std::to_string(needed) +
                                " texels exceed the driver's buffer textures (" + std::to_string(max_texels_) +
                                "); the passes read storage buffers and the raster stages splats in shared memory");
        fetch = RasterFetch::shared;
    }
    return fetch;
}

// With texel fetches (fetch_in_use_ texel), buffer-texture views of what each pass reads, re-pointed
// every frame. Step 1b: the Gaussians, SH and instances (unsigned words: bit-exact).
void SplatPass::bind_project_texels() {
    engine::gl::bind_buffer_texture(gaussian_texels_, "splat gaussian texels", GL_RGBA32UI, scene_.gaussians(),
                                    SPLAT_TEXTURE_GAUSSIANS);
    engine::gl::bind_buffer_texture(sh_texels_, "splat sh texels", GL_RGB32UI, scene_.sh(), SPLAT_TEXTURE_SH);
    engine::gl::bind_buffer_texture(instance_texels_, "splat instance texels", GL_RGBA32UI, scene_.instances(),
                                    SPLAT_TEXTURE_INSTANCES);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // uploaded as buffers, read as texels
}

// Step 3: the projected splats (as words) and the scanned key offsets.
void SplatPass::bind_bin_texels() {
    engine::gl::bind_buffer_texture(projected_words_, "splat projected words", GL_RGBA32UI, projected_,
                                    SPLAT_TEXTURE_PROJECTED_WORDS);
    engine::gl::bind_buffer_texture(key_offset_texels_, "splat key offset texels", GL_R32UI, tile_counts_,
                                    SPLAT_TEXTURE_KEY_OFFSETS);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // written through storage buffers, read as texels
}

// Step 5: the sorted keys.
void SplatPass::bind_ranges_texels() {
    engine::gl::bind_buffer_texture(key_texels_, "splat sorted key texels", GL_RG32UI, keys_,
                                    SPLAT_TEXTURE_SORTED_KEYS);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // sorted through storage buffers, read as texels
}

// Step 6: the projected splats and the sorted values.
void SplatPass::bind_raster_texels() {
    engine::gl::bind_buffer_texture(projected_texels_, "splat projected texels", GL_RGBA32F, projected_,
                                    SPLAT_TEXTURE_PROJECTED);
    engine::gl::bind_buffer_texture(value_texels_, "splat value texels", GL_R32UI, values_, SPLAT_TEXTURE_VALUES);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // written through storage buffers, read as texels
}

// Steps 6 and 7 of execute.
void SplatPass::record_raster(engine::FrameContext& frame, const RasterSize& raster) {
    {  // 6. per-tile front-to-back raster, stopping at the mesh depth; composite C + T·mesh, or below
       //    render scale 1, C and A with their derivatives at low resolution
        GpuTimerScope t(frame.timers, "splat.raster");
        bind_all(frame);
        std::vector<std::string> defines{"RASTER_TILE_SIZE=" + std::to_string(raster.tile_size)};
        if (raster.upscaled) defines.push_back("SPLAT_GRADIENTS");
        if (fetch_in_use_ == RasterFetch::shared)
            defines.push_back("RASTER_FETCH_SHARED");
        else
            bind_raster_texels();
        const auto& raster_program = frame.shaders.program({"splat_lod/splat_tile_raster.comp.glsl"}, defines);
        glUseProgram(raster_program.id());
        glDispatchCompute(raster.tiles_x, raster.tiles_y, 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                        GL_TEXTURE_UPDATE_BARRIER_BIT);
    }
    if (raster.upscaled) {  // 7. upscale to the output and composite over the mesh pass
        GpuTimerScope t(frame.timers, "splat.upscale");
        const std::string method = "UPSCALE_METHOD=" + std::to_string(static_cast<int>(settings.lod.upscaler));
        glUseProgram(frame.shaders.program({"splat_lod/splat_upscale.comp.glsl"}, {method}).id());
        glDispatchCompute(groups(static_cast<std::uint32_t>(frame.target.width()), SPLAT_UPSCALE_WORKGROUP_SIZE),
                          groups(static_cast<std::uint32_t>(frame.target.height()), SPLAT_UPSCALE_WORKGROUP_SIZE), 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                        GL_TEXTURE_UPDATE_BARRIER_BIT);
    }
}

void SplatPass::execute(engine::FrameContext& frame) {
    collect_statistics(frame.bus, false);
    std::vector<const SplatComponent*> components;
    for (const auto* c : frame.scene.components<SplatComponent>())
        if (c->cloud && !c->cloud->empty()) components.push_back(c);
    scene_.update(components);
    const std::uint32_t n = scene_.gaussian_count();
    if (n == 0) return;
    if (!scan_) {
        scan_ = std::make_unique<engine::gl::PrefixScan>(frame.shaders);
        sort_ = std::make_unique<engine::gl::RadixSort>(frame.shaders);
    }
    const RasterSize raster = raster_size(frame);
    if (raster.upscaled)
        ensure_low_res_images(raster.width, raster.height);
    else if (low_.width > 0)
        low_ = LowResImages{};  // back at native resolution: nothing keeps them
    ensure_frame_buffers(n, raster.tiles_x * raster.tiles_y);
    fetch_in_use_ = resolve_fetch(n);
    upload_frame_uniforms(frame, raster);
    clear_frame_buffers();
    record_selection(frame, n);     // 1. a–d: cull, skip, project, the splat budget
    record_sort(frame, n, raster);  // 2–5. scan, bin, sort, tile ranges
    record_raster(frame, raster);   // 6. raster; 7. upscale below render scale 1
    glUseProgram(0);
    record_statistics(frame);
}

// The per-frame counters, the budget's histograms, the tile ranges and counts start at zero, and the
// cluster list empty, before step 1 fills them.
void SplatPass::clear_frame_buffers() {
    glClearNamedBufferData(counters_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    if (settings.lod.splat_budget > 0)
        glClearNamedBufferData(budget_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    glClearNamedBufferData(tile_ranges_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    // Gaussians of skipped clusters are never visited: their tile counts stay 0.
    glClearNamedBufferData(tile_counts_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    const glm::uvec4 no_clusters(0u, 1u, 1u, 0u);
    cluster_list_.upload(0, sizeof(no_clusters), &no_clusters);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

// Steps 2–5: the splats' key ranges, their (depth, tile) keys, the sort and each tile's range of keys.
void SplatPass::record_sort(engine::FrameContext& frame, std::uint32_t n, const RasterSize& raster) {
    {  // 2. exclusive scan of tile counts: each splat's key range; the total lands at [n]
        GpuTimerScope t(frame.timers, "splat.scan");
        scan_->record({tile_counts_, count_, 0, n, tile_counts_, std::size_t(n) * sizeof(std::uint32_t)});
    }
    {  // 3. bin: one (depth, tile) key per tile touched, within the key capacity
        GpuTimerScope t(frame.timers, "splat.bin");
        bind_all(frame);
        glUseProgram(program(frame, "splat_dispatch_args.comp.glsl").id());
        glDispatchCompute(1, 1, 1);
        glUseProgram(texel_program(frame, "splat_bin.comp.glsl", &SplatPass::bind_bin_texels).id());
        glDispatchCompute(groups(n, SPLAT_BIN_WORKGROUP_SIZE), 1, 1);
        barrier();
    }
    {  // 4. stable radix sort by (tile, depth); the key count stays on the GPU
        GpuTimerScope t(frame.timers, "splat.sort");
        const auto hi_bits = raster.key_depth_bits > 0
                                 ? 0u
                                 : static_cast<std::uint32_t>(std::bit_width(raster.tiles_x * raster.tiles_y));
        sort_->record({keys_, values_, args_, 3 * sizeof(std::uint32_t), key_capacity_, hi_bits,
                       fetch_in_use_ == RasterFetch::texel});
    }
    {  // 5. tile ranges in the sorted keys
        GpuTimerScope t(frame.timers, "splat.ranges");
        bind_all(frame);
        glUseProgram(texel_program(frame, "splat_tile_ranges.comp.glsl", &SplatPass::bind_ranges_texels).id());
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, args_.id());
        glDispatchComputeIndirect(0);
        barrier();
    }
}

void SplatPass::record_statistics(engine::FrameContext& frame) {
    Readback& r = readbacks_[frames_ % readbacks_.size()];
    if (r.fence.pending()) collect_statistics(frame.bus, true);  // all four in flight: rare, bounded
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glCopyNamedBufferSubData(counters_.id(), r.buffer.id(), 0, 0, sizeof(gpu::FrameCounters));
    r.fence.insert();
    r.frame = frame.frame_index;
    r.considered = scene_.live_gaussians();
    r.splat_budget = settings.lod.splat_budget;
    r.size_threshold_px = settings.lod.rule.size_threshold_px;
    r.resident_bytes = scene_.resident_bytes() + projected_.size() + tile_counts_.size() + keys_.size() +
                       values_.size() + tile_ranges_.size() + cluster_list_.size() + low_res_bytes();
    ++frames_;
}

void SplatPass::collect_statistics(engine::MessageBus& bus, bool wait) {
    for (std::size_t k = 0; k < readbacks_.size(); ++k) {
        Readback& r = readbacks_[(frames_ + k) % readbacks_.size()];  // oldest first
        if (!r.fence.pending()) continue;
        if (!wait && !r.fence.signalled()) continue;
        gpu::FrameCounters c;
        glGetNamedBufferSubData(r.buffer.id(), 0, sizeof(c), &c);
        r.fence.reset();
        plugin_msgs::SplatStatistics s;
        s.frame_index = r.frame;
        s.considered = r.considered;  // the clouds' Gaussians, not the slots padded to cluster boundaries
        s.visible = c.visible;
        for (int l = 0; l < 4; ++l) s.per_level[static_cast<std::size_t>(l)] = c.per_level[l];
        s.skipped = c.skipping.x;
        s.culled = c.skipping.y;
        s.hidden = c.skipping.z;
        s.splat_budget = r.splat_budget;
        s.unbudgeted = r.splat_budget > 0 ? c.budget.z : c.visible;
        s.budget_scale =
            r.splat_budget > 0 ? std::exp2(static_cast<double>(c.budget.x) / SPLAT_BUDGET_BINS_PER_OCTAVE) : 1.0;
        s.budget_threshold_px = s.budget_scale * r.size_threshold_px;
        s.budget_coverage_cut_px = r.splat_budget > 0 && c.budget.y > 0
                                       ? std::exp2((static_cast<double>(c.budget.y) - SPLAT_COVERAGE_BIN_OFFSET) /
                                                   SPLAT_BUDGET_BINS_PER_OCTAVE)
                                       : 0.0;
        s.tile_splat_pairs = c.keys_needed;
        s.key_capacity = key_capacity_;
        s.overflowed = c.overflowed != 0;
        s.resident_bytes = r.resident_bytes;
        if (s.overflowed) {
            // That frame dropped tile-splat pairs; the next frames get room for them.
            if (c.keys_needed > pending_growth_)
                engine::log_warning("splat_lod: frame " + std::to_string(r.frame) + " needed " +
                                    std::to_string(c.keys_needed) + " tile-splat pairs but the buffer holds " +
                                    std::to_string(key_capacity_) + "; growing it");
            pending_growth_ = std::max(pending_growth_, c.keys_needed);
        }
        if (!latest_ || latest_->frame_index <= s.frame_index) latest_ = s;
        bus.publish(s);
    }
}

upscale::GradientImage SplatPass::read_low_res_image() const {
    upscale::GradientImage image;
    if (low_.width == 0) return image;
    image.width = low_.width;
    image.height = low_.height;
    std::vector<float>* channels[] = {&image.value, &image.dx, &image.dy, &image.dxy};
    const std::size_t floats = std::size_t(low_.width) * std::size_t(low_.height) * 4;
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    for (int k = 0; k < 4; ++k) {
        channels[k]->resize(floats);
        glGetTextureImage(low_.images[k].id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(floats * sizeof(float)),
                          channels[k]->data());
    }
    return image;
}

std::vector<float> SplatPass::read_low_res_front_depth() const {
    std::vector<float> depth(std::size_t(low_.width) * std::size_t(low_.height));
    if (depth.empty()) return depth;
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glGetTextureImage(low_.front.id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(depth.size() * sizeof(float)),
                      depth.data());
    return depth;
}

std::uint64_t SplatPass::low_res_bytes() const {
    return std::uint64_t(low_.width) * std::uint64_t(low_.height) * (4 * 16 + 4);
}

// glGetNamedBufferSubData waits for the copy, so reading with `wait` blocks until it is done.
void SplatPass::wait_for_statistics(engine::MessageBus& bus) {
    collect_statistics(bus, true);
}

}  // namespace splat_lod
