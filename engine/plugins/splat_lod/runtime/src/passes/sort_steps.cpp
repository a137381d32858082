// Steps 2–5 of the splat frame (frame_steps.h): the clusters' key ranges, the splats' (depth, tile) keys,
// the sort and each tile's range of keys.
#include <bit>

#include "engine/gl/compute_step.h"
#include "engine/gl/gpu_timers.h"
#include "passes/frame_steps.h"

namespace splat_lod {

void record_scan(const FrameSteps& steps, std::uint32_t clusters) {
    // 2. exclusive scan of the clusters' pair counts: each cluster's first key; the total lands at [clusters]
    engine::gl::GpuTimerScope t(steps.frame.timers, "splat.scan");
    FrameBuffers& b = steps.buffers;
    steps.scan.record(
        {b.cluster_pairs, b.count, 0, clusters, b.cluster_pairs, std::size_t(clusters) * sizeof(std::uint32_t)});
}

void record_sort(const FrameSteps& steps) {
    using engine::gl::GpuTimerScope;
    FrameBuffers& b = steps.buffers;
    {  // 3. bin: one (depth, tile) key per tile touched, within the key capacity
        GpuTimerScope t(steps.frame.timers, "splat.bin");
        steps.bind_all();
        engine::gl::run({.program = &steps.program("splat_dispatch_args.comp.glsl")});
        const auto& bin = steps.input_program(
            "splat_bin.comp.glsl", [&] { steps.texels.bind_bin(b); }, steps.key_defines());
        engine::gl::run({.program = &bin, .indirect = &b.cluster_list, .barrier = kStepBarrier});
    }
    {  // 4. stable radix sort by (tile, depth); the key count stays on the GPU
        GpuTimerScope t(steps.frame.timers, "splat.sort");
        const RasterSize& r = steps.raster;
        const auto hi_bits = steps.one_word_keys() ? 0u : static_cast<std::uint32_t>(std::bit_width(r.tile_count()));
        steps.sort.record({b.keys, b.values, b.args, 3 * sizeof(std::uint32_t), b.key_capacity, hi_bits,
                           steps.one_word_keys() ? 1u : 2u, steps.fetch == RasterFetch::texel});
    }
    {  // 5. tile ranges in the sorted keys
        GpuTimerScope t(steps.frame.timers, "splat.ranges");
        steps.bind_all();
        const auto& ranges = steps.input_program(
            "splat_tile_ranges.comp.glsl", [&] { steps.texels.bind_ranges(b, steps.one_word_keys()); },
            steps.key_defines());
        engine::gl::run({.program = &ranges, .indirect = &b.args, .barrier = kStepBarrier});
    }
}

}  // namespace splat_lod
