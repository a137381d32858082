// Steps 1 and 2 of the splat frame (frame_steps.h): which Gaussians the view draws, and how many splats
// and tile-splat pairs that makes.
#include <cstddef>
#include <string>

#include "engine/core/log.h"
#include "engine/gl/compute_step.h"
#include "engine/gl/gpu_timers.h"
#include "passes/frame_steps.h"

namespace splat_lod {

void record_selection(const FrameSteps& steps, std::uint32_t gaussians) {
    using engine::gl::groups_for;
    engine::gl::GpuTimerScope t(steps.frame.timers, "splat.project");
    steps.bind_all();
    // a. one invocation per project workgroup (a cluster): culled, skipped, or listed for b
    const std::uint32_t clusters = groups_for(gaussians, SPLAT_PROJECT_WORKGROUP_SIZE);
    engine::gl::run({.program = &steps.program("splat_clusters.comp.glsl"),
                     .groups = {groups_for(clusters, SPLAT_CLUSTER_WORKGROUP_SIZE), 1, 1},
                     .barrier = GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT});
    // b. the listed clusters' Gaussians, dispatched from the list's header
    const auto& project =
        steps.input_program("splat_project.comp.glsl", [&] { steps.texels.bind_project(steps.scene); });
    engine::gl::run({.program = &project, .indirect = &steps.buffers.cluster_list, .barrier = kStepBarrier});
    if (steps.lod.splat_budget == 0) return;
    // c. the budget's scale β from the selected Gaussians' coverage histogram; d. keep those selected at β
    engine::gl::run({.program = &steps.program("splat_budget.comp.glsl"), .barrier = kStepBarrier});
    engine::gl::run({.program = &steps.storage_program("splat_budget_trim.comp.glsl"),
                     .indirect = &steps.buffers.cluster_list,
                     .barrier = kStepBarrier});
}

FrameCounts select_splats(const FrameSteps& steps, gpu::FrameUniforms& uniforms, std::uint32_t gaussians,
                          const StripRoom& room) {
    FrameBuffers& b = steps.buffers;
    const std::uint32_t clusters = engine::gl::groups_for(gaussians, SPLAT_PROJECT_WORKGROUP_SIZE);
    const bool splittable = uniforms.strip_end_row - uniforms.strip_first_row > 1;
    FrameCounts counts;
    for (counts.selection_runs = 1;; ++counts.selection_runs) {
        uniforms.splat_capacity = b.splat_capacity;
        b.uniforms.upload(0, sizeof(uniforms), &uniforms);
        if (uniforms.strip_first_row == 0)
            b.clear(steps.lod.splat_budget > 0);
        else
            b.clear_strip();
        record_selection(steps, gaussians);
        record_scan(steps, clusters);
        // The strip's one wait: the two counts, before the steps that are sized by them are recorded.
        engine::gl::memory_barrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        engine::gl::read_buffer(b.counters, offsetof(gpu::FrameCounters, projected), sizeof(std::uint32_t),
                                &counts.splats);
        engine::gl::read_buffer(b.cluster_pairs, std::size_t(clusters) * sizeof(std::uint32_t), sizeof(std::uint32_t),
                                &counts.pairs);
        counts.fits = counts.splats <= room.splats && counts.pairs <= room.pairs;
        if (!counts.fits && splittable) return counts;  // drawn in two halves instead
        if (counts.splats <= b.splat_capacity || counts.selection_runs == 2) break;
        b.ensure_splats(counts.splats, room.splats);  // the clusters that did not fit wrote nothing: again, with room
    }
    if (counts.splats <= b.splat_capacity) return counts;
    engine::log_warning("splat_lod: " + std::to_string(counts.splats) + " projected splats exceed the " +
                        std::to_string(b.splat_capacity) + " the frame can hold; some are not drawn");
    return counts;
}

}  // namespace splat_lod
