// Step 1 of the splat frame (frame_steps.h): which Gaussians the view draws.
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

}  // namespace splat_lod
