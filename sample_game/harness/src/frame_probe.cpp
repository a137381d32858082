#include "sample_game/harness/frame_probe.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <vector>

#include <plugin_msgs/frame_statistics.h>

#include "engine/gl/compute_step.h"
#include "engine/gl/gpu_timers.h"
#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "splat_lod/eval/temporal_sweep.h"
#include "splat_lod/splat_renderer.h"

namespace sample_game {
namespace {

double draw(engine::Engine& engine, const engine::Scene& scene, const engine::CameraView& camera,
            engine::RenderTarget& target) {
    const auto start = std::chrono::steady_clock::now();
    engine.renderer().render(scene, camera, target);
    engine::gl::finish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The GPU spans of the newest completed frame (after GpuTimers::wait_all(): this one).
void record_spans(engine::Engine& engine, FrameRecord& r) {
    const auto& spans = engine.renderer().timers().latest();
    if (!spans) return;
    for (const auto& [name, ms] : engine::gl::span_totals(*spans)) {  // a strip of the splat pass: a span each
        double* field = name == "mesh"            ? &r.gpu_mesh_ms
                        : name == "splat"         ? &r.gpu_splat_ms
                        : name == "splat.project" ? &r.gpu_project_ms
                        : name == "splat.scan"    ? &r.gpu_scan_ms
                        : name == "splat.bin"     ? &r.gpu_bin_ms
                        : name == "splat.sort"    ? &r.gpu_sort_ms
                        : name == "splat.ranges"  ? &r.gpu_ranges_ms
                        : name == "splat.raster"  ? &r.gpu_raster_ms
                        : name == "splat.upscale" ? &r.gpu_upscale_ms
                        : name == "fog"           ? &r.gpu_fog_ms
                                                  : nullptr;
        if (field) *field = ms;
    }
}

}  // namespace

void draw_and_measure(GameWorld& world, engine::Engine& engine, const engine::CameraView& camera,
                      engine::RenderTarget& target, FrameRecord& record) {
    splat_lod::SplatRenderer& pass = world.pass();
    // The splat pass publishes no statistics for a frame without Gaussians: only numbers of the
    // frame just drawn count (the renderer's index was that frame's during render()).
    auto this_frames_statistics = [&]() -> const plugin_msgs::SplatStatistics* {
        const auto& s = pass.latest_statistics();
        return s && s->frame_index + 1 == engine.renderer().frame_index() ? &*s : nullptr;
    };
    record.frame_ms = draw(engine, world.scene(), camera, target);
    record.gpu_upload_bytes = pass.memory().last_upload_bytes;
    engine.renderer().timers().wait_all();
    pass.wait_for_statistics(engine.bus());
    record.redraws = 0;
    while (this_frames_statistics() && this_frames_statistics()->overflowed && record.redraws < kMaxRedraws) {
        ++record.redraws;
        record.frame_ms = draw(engine, world.scene(), camera, target);
        engine.renderer().timers().wait_all();
        pass.wait_for_statistics(engine.bus());
    }
    record_spans(engine, record);
    if (const auto frame = engine.bus().latest<plugin_msgs::FrameStatistics>())
        record.cpu_record_ms = frame->cpu_frame_ms;
    record.considered = pass.memory().live_gaussians;
    if (const plugin_msgs::SplatStatistics* s = this_frames_statistics()) {
        record.considered = s->considered;
        record.visible = s->visible;
        record.skipped = s->skipped;
        record.culled = s->culled;
        record.hidden = s->hidden;
        record.unbudgeted = s->unbudgeted;
        record.budget_threshold_px = s->budget_threshold_px;
        record.tile_splat_pairs = s->tile_splat_pairs;
        record.drawn_per_level = s->per_level;
        record.gpu_total_bytes = s->resident_bytes;
    }
    const splat_lod::SplatMemory memory = pass.memory();
    record.gpu_page_bytes = std::uint64_t(memory.pages_in_use) * memory.page_bytes;
    record.gpu_scene_bytes = memory.scene_bytes;
    record.gpu_frame_bytes = memory.frame_bytes;
    record.selection_runs = static_cast<int>(memory.selection_runs);
    record.strips = static_cast<int>(memory.strips);
    record_streaming(world, record);
}

void measure_stereo(GameWorld& world, engine::Engine& engine, const engine::CameraView& camera, float ipd,
                    engine::RenderTarget& target, FrameRecord& record) {
    const engine::StereoEyes eyes = engine::stereo_eyes(camera, ipd);
    record.stereo_frame_ms = 0.0;
    std::vector<engine::Image> images;
    for (const engine::CameraView* eye : {&eyes.left, &eyes.right}) {
        record.stereo_frame_ms += draw(engine, world.scene(), *eye, target);
        images.push_back(target.read_color());  // not timed
    }
    record.stereo_eye_psnr = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < 2; ++k) {
        engine::CameraView own = k == 0 ? eyes.left : eyes.right;
        own.selection_view.reset();
        draw(engine, world.scene(), own, target);
        record.stereo_eye_psnr =
            std::min(record.stereo_eye_psnr, engine::compare_images(images[k], target.read_color()).psnr_db);
    }
    engine.renderer().timers().wait_all();
    world.pass().wait_for_statistics(engine.bus());
}

void measure_switch_pop(GameWorld& world, engine::Engine& engine, const engine::CameraView& camera,
                        const engine::CameraView& previous, const engine::Image& image, engine::RenderTarget& target,
                        FrameRecord& record) {
    draw(engine, world.scene(), splat_lod::eval::with_selection_of(camera, previous), target);
    record.switch_pop = splat_lod::eval::selection_switch_pop(splat_lod::eval::to_float(target.read_color()),
                                                              splat_lod::eval::to_float(image));
    engine.renderer().timers().wait_all();
    world.pass().wait_for_statistics(engine.bus());
}

void record_pose(const GameWorld& world, const PathPose& pose, FrameRecord& record) {
    const WorldGround& ground = world.ground();
    record.segment = pose.segment;
    record.t = pose.t;
    record.eye = pose.eye;
    record.height_above_ground_m = pose.eye.y - ground.height(pose.eye.x, pose.eye.z);
    record.distance_to_centre_m = glm::distance(pose.eye, ground.centre());
}

void record_streaming(GameWorld& world, FrameRecord& record) {
    const auto& streamer = world.streamer();
    record.resident_bytes = streamer.resident_bytes();
    record.props_gpu_bytes = world.props_gpu_bytes();
    record.stream_upload_bytes = streamer.stats().uploaded_bytes_last_update;
    record.failures_total = streamer.stats().failures;
    record.chunks = world.census();
    record.chunks_drawn = streamer.residency().drawn_chunks;
    record.groups_drawn = streamer.residency().drawn_groups;
}

}  // namespace sample_game
