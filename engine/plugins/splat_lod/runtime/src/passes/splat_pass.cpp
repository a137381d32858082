#include "passes/splat_pass.h"

#include <algorithm>
#include <vector>

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
    // starts at what the last frame's largest strip projected; the keys are sized by what each strip needs.
    const StripRoom room = lod_.splat_budget > 0 ? StripRoom{}
                                                 : strip_room(settings.frame_memory_limit, last_counts_.splats,
                                                              last_counts_.pairs, raster.key_depth_bits > 0 ? 1u : 2u);
    buffers_.ensure(engine::gl::groups_for(n, SPLAT_PROJECT_WORKGROUP_SIZE), raster.tile_count());
    std::uint32_t largest_strip = 0;  // splats
    for (const DrawnStrip& s : last_strips_) largest_strip = std::max(largest_strip, s.splats);
    buffers_.ensure_splats(largest_strip, room.splats);
    fetch_in_use_ =
        texels_.resolve(settings.raster_fetch, buffers_.splat_capacity, buffers_.key_capacity, scene_, fetch_in_use_);
    gpu::FrameUniforms uniforms = frame_uniforms(settings, lod_, frame, raster, scene_);
    FrameSteps steps{frame, settings, lod_,    raster,        scene_, buffers_,
                     low_,  depth_,   texels_, fetch_in_use_, *scan_, *sort_};
    const bool picked = picks_.upload(frame.picks, raster.scale, {raster.width, raster.height}, buffers_.picks);
    last_counts_ = draw_strips(steps, uniforms, room, picked);  // 1–6 per strip of tile rows
    record_upscale(steps);                                      // 7. below render scale 1
    if (picked) picks_.record(buffers_.picks, frame.camera, scene_.instance_components());
    engine::gl::end_steps();

    FrameStatistics::Frame facts;
    facts.index = frame.frame_index;
    facts.considered = scene_.live_gaussians();
    facts.splat_budget = lod_.splat_budget;
    facts.size_threshold_px = lod_.rule.size_threshold_px;
    facts.resident_bytes = scene_.resident_bytes() + frame_bytes();
    statistics_.record(facts, buffers_, frame.bus);
}

// The strips planned from the last frame's (frame_strips.h), top to bottom; a strip that needs more than
// its room is drawn in two halves, down to single rows (SplatPassSettings::frame_memory_limit).
FrameCounts SplatPass::draw_strips(FrameSteps& steps, gpu::FrameUniforms& uniforms, const StripRoom& room,
                                   bool picked) {
    std::vector<DrawnStrip> todo = plan_strips(room, last_strips_, steps.raster.tiles_y);
    std::reverse(todo.begin(), todo.end());  // the next at the back
    last_strips_.clear();
    FrameCounts counts{.selection_runs = 1, .strips = 0};
    while (!todo.empty()) {
        const DrawnStrip rows = todo.back();
        todo.pop_back();
        uniforms.strip_first_row = rows.first_row;
        uniforms.strip_end_row = rows.end_row;
        const FrameCounts strip = select_splats(steps, uniforms, scene_.gaussian_count(), room);
        const bool split = !strip.fits && rows.end_row - rows.first_row > 1;
        counts.selection_runs += strip.selection_runs - (split ? 0 : 1);
        if (split) {
            const std::uint32_t middle = (rows.first_row + rows.end_row) / 2;
            todo.push_back({middle, rows.end_row, 0, 0});
            todo.push_back({rows.first_row, middle, 0, 0});
            continue;
        }
        draw_strip(steps, uniforms, strip, room, picked);
        last_strips_.push_back({rows.first_row, rows.end_row, strip.splats, strip.pairs});
        counts.splats += strip.splats;
        counts.pairs += strip.pairs;
        ++counts.strips;
    }
    return counts;
}

// Steps 3–6 of a strip whose steps 1–2 have run.
void SplatPass::draw_strip(FrameSteps& steps, gpu::FrameUniforms& uniforms, const FrameCounts& strip,
                           const StripRoom& room, bool picked) {
    buffers_.ensure_keys(strip.pairs, steps.one_word_keys() ? 1 : 2, room.pairs);
    fetch_in_use_ =
        texels_.resolve(settings.raster_fetch, buffers_.splat_capacity, buffers_.key_capacity, scene_, fetch_in_use_);
    steps.fetch = fetch_in_use_;  // the buffers may have outgrown the driver's buffer textures
    uniforms.key_capacity = buffers_.key_capacity;
    buffers_.uniforms.upload(0, sizeof(uniforms), &uniforms);
    record_sort(steps);               // 3–5. bin, sort, tile ranges
    if (picked) record_picks(steps);  // 5½. the splats under the pixels picked in the strip
    record_raster(steps, uniforms.strip_end_row - uniforms.strip_first_row);  // 6. raster
    buffers_.strip_drawn();
}

std::uint64_t SplatPass::frame_bytes() const {
    return buffers_.bytes() + low_.bytes() + depth_.bytes() + (scan_ ? scan_->bytes() : 0) +
           (sort_ ? sort_->bytes() : 0);
}

std::uint64_t SplatPass::view_bytes() const {
    return buffers_.projected.size() + buffers_.keys.size() + buffers_.values.size() + (sort_ ? sort_->bytes() : 0);
}

// The readback waits for each copy, so reading with `wait` blocks until every frame's is done.
void SplatPass::wait_for_statistics(engine::MessageBus& bus) {
    statistics_.collect(buffers_, bus, true);
}

}  // namespace splat_lod
