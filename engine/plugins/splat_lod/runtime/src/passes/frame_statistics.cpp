// The splat frame's statistics readback (frame_statistics.h).
#include "passes/frame_statistics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/log.h"
#include "engine/gl/compute_step.h"
#include "gpu/gpu_layout.h"

namespace splat_lod {
namespace {

plugin_msgs::SplatStatistics statistics_of(const FrameStatistics::Frame& f, const gpu::FrameCounters& c,
                                           std::uint32_t key_capacity) {
    plugin_msgs::SplatStatistics s;
    s.frame_index = f.index;
    s.considered = f.considered;
    s.visible = c.visible;
    for (int l = 0; l < 4; ++l) s.per_level[static_cast<std::size_t>(l)] = c.per_level[l];
    s.skipped = c.skipping.x;
    s.culled = c.skipping.y;
    s.hidden = c.skipping.z;
    s.splat_budget = f.splat_budget;
    s.unbudgeted = f.splat_budget > 0 ? c.budget.z : c.visible;
    s.budget_scale =
        f.splat_budget > 0 ? std::exp2(static_cast<double>(c.budget.x) / SPLAT_BUDGET_BINS_PER_OCTAVE) : 1.0;
    s.budget_threshold_px = s.budget_scale * f.size_threshold_px;
    s.budget_coverage_cut_px =
        f.splat_budget > 0 && c.budget.y > 0
            ? std::exp2((static_cast<double>(c.budget.y) - SPLAT_COVERAGE_BIN_OFFSET) / SPLAT_BUDGET_BINS_PER_OCTAVE)
            : 0.0;
    s.tile_splat_pairs = c.keys_needed;
    s.key_capacity = key_capacity;
    s.overflowed = c.overflowed != 0;
    s.resident_bytes = f.resident_bytes;
    return s;
}

}  // namespace

void FrameStatistics::record(const Frame& frame, FrameBuffers& buffers, engine::MessageBus& bus) {
    Readback& r = readbacks_[frames_ % readbacks_.size()];
    if (!r.buffer) {
        r.buffer = engine::gl::Buffer("splat counters readback");
        r.buffer.storage(sizeof(gpu::FrameCounters), nullptr, GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
    }
    if (r.fence.pending()) collect(buffers, bus, true);  // all four in flight: rare, bounded
    engine::gl::memory_barrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    engine::gl::copy_buffer(buffers.counters, r.buffer, sizeof(gpu::FrameCounters));
    r.fence.insert();
    r.frame = frame;
    ++frames_;
}

void FrameStatistics::collect(FrameBuffers& buffers, engine::MessageBus& bus, bool wait) {
    for (std::size_t k = 0; k < readbacks_.size(); ++k) {
        Readback& r = readbacks_[(frames_ + k) % readbacks_.size()];  // oldest first
        if (!r.fence.pending()) continue;
        if (!wait && !r.fence.signalled()) continue;
        gpu::FrameCounters c;
        engine::gl::read_buffer(r.buffer, 0, sizeof(c), &c);  // waits for the copy
        r.fence.reset();
        const plugin_msgs::SplatStatistics s = statistics_of(r.frame, c, buffers.key_capacity);
        if (s.overflowed)  // the keys are sized by the frame's need, up to the sort's limit
            engine::log_warning("splat_lod: frame " + std::to_string(r.frame.index) + " needed " +
                                std::to_string(c.keys_needed) + " tile-splat pairs, more than the sort's " +
                                std::to_string(buffers.key_capacity) + "; some were dropped");
        if (!latest_ || latest_->frame_index <= s.frame_index) latest_ = s;
        bus.publish(s);
    }
}

}  // namespace splat_lod
