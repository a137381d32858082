#include "passes/splat_pass.h"

#include "engine/core/message_bus.h"
#include "engine/gl/compute_step.h"
#include "engine/gl/prefix_scan.h"
#include "engine/gl/radix_sort.h"
#include "engine/render/render_target.h"
#include "engine/scene/scene.h"
#include "passes/frame_steps.h"
#include "passes/frame_uniforms.h"
#include "splat_lod/splat_component.h"

namespace splat_lod {

SplatPass::SplatPass() = default;
SplatPass::~SplatPass() = default;

void SplatPass::apply(const plugin_msgs::LodSettings& lod) {
    lod_ = lod;
}

void SplatPass::execute(engine::FrameContext& frame) {
    statistics_.collect(buffers_, frame.bus, false);
    std::vector<const SplatComponent*> components;
    for (const auto* c : frame.scene.components<SplatComponent>())
        if (c->cloud && !c->cloud->empty()) components.push_back(c);
    scene_.update(components, settings.gpu_storage);
    const std::uint32_t n = scene_.gaussian_count();
    if (n == 0) return;
    if (!scan_) {
        scan_ = std::make_unique<engine::gl::PrefixScan>(frame.shaders);
        sort_ = std::make_unique<engine::gl::RadixSort>(frame.shaders);
    }
    const RasterSize raster = raster_size(settings, lod_, frame.target.width(), frame.target.height());
    if (raster.upscaled)
        low_.ensure(raster.width, raster.height);
    else if (low_.width > 0)
        low_ = LowResImages{};  // back at native resolution: nothing keeps them
    if (settings.splat_depth)
        depth_.ensure(frame.target.width(), frame.target.height());
    else if (depth_.width > 0)
        depth_ = SplatDepthImage{};
    // Step 1 walks the scene's n Gaussian slots, a cluster of them per workgroup. The dense splat array
    // starts at what the last frame projected; the keys are sized by what this one needs.
    buffers_.ensure(engine::gl::groups_for(n, SPLAT_PROJECT_WORKGROUP_SIZE), raster.tile_count());
    buffers_.ensure_splats(last_counts_.splats);
    fetch_in_use_ =
        texels_.resolve(settings.raster_fetch, buffers_.splat_capacity, buffers_.key_capacity, scene_, fetch_in_use_);
    gpu::FrameUniforms uniforms = frame_uniforms(settings, lod_, frame, raster, scene_);
    FrameSteps steps{frame, settings, lod_,    raster,        scene_, buffers_,
                     low_,  depth_,   texels_, fetch_in_use_, *scan_, *sort_};
    last_counts_ = select_splats(steps, uniforms, n);  // 1. a–d: cull, skip, project, the budget; 2. scan
    buffers_.ensure_keys(last_counts_.pairs, steps.one_word_keys() ? 1 : 2);
    fetch_in_use_ =
        texels_.resolve(settings.raster_fetch, buffers_.splat_capacity, buffers_.key_capacity, scene_, fetch_in_use_);
    steps.fetch = fetch_in_use_;  // the buffers may have outgrown the driver's buffer textures
    uniforms.key_capacity = buffers_.key_capacity;
    buffers_.uniforms.upload(0, sizeof(uniforms), &uniforms);
    record_sort(steps);  // 3–5. bin, sort, tile ranges
    if (picks_.upload(frame.picks, raster.scale, {raster.width, raster.height}, buffers_.picks)) {
        record_picks(steps);  // 5½. the splats under the pixels picked
        picks_.record(buffers_.picks, frame.camera, scene_.instance_components());
    }
    record_raster(steps);  // 6. raster; 7. upscale below render scale 1
    engine::gl::end_steps();

    FrameStatistics::Frame facts;
    facts.index = frame.frame_index;
    facts.considered = scene_.live_gaussians();
    facts.splat_budget = lod_.splat_budget;
    facts.size_threshold_px = lod_.rule.size_threshold_px;
    facts.resident_bytes = scene_.resident_bytes() + frame_bytes();
    statistics_.record(facts, buffers_, frame.bus);
}

std::uint64_t SplatPass::frame_bytes() const {
    return buffers_.bytes() + low_.bytes() + depth_.bytes() + (scan_ ? scan_->bytes() : 0) +
           (sort_ ? sort_->bytes() : 0);
}

// The readback waits for each copy, so reading with `wait` blocks until every frame's is done.
void SplatPass::wait_for_statistics(engine::MessageBus& bus) {
    statistics_.collect(buffers_, bus, true);
}

}  // namespace splat_lod
