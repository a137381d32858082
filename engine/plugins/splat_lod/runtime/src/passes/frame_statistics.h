#pragma once
// The splat frame's statistics: each frame's GPU counters copied into one of four readback buffers
// behind a fence, read when the GPU is done (never stalling a frame, unless all four are in flight)
// and published on the bus as plugin_msgs::SplatStatistics. A frame whose keys overflowed (more than
// the sort can take) is logged.
#include <array>
#include <cstdint>
#include <optional>

#include "splat_lod/msgs/splat_statistics.h"

#include "engine/core/message_bus.h"
#include "engine/gl/objects.h"
#include "passes/frame_buffers.h"

namespace splat_lod {

class FrameStatistics {
public:
    // What the CPU knows of a frame when it is drawn.
    struct Frame {
        std::uint64_t index = 0;
        std::uint64_t considered = 0;      // the clouds' Gaussians, not the slots padded to cluster boundaries
        std::uint64_t resident_bytes = 0;  // the scene, the frame buffers and the low-resolution images
        std::uint32_t splat_budget = 0;
        float size_threshold_px = 0.0f;
    };
    // Copies this frame's counters (after the last step); waits for the oldest readback first when all
    // four are in flight.
    void record(const Frame& frame, FrameBuffers& buffers, engine::MessageBus& bus);
    // Publishes every readback the GPU has finished (`wait`: every pending one), oldest first.
    void collect(FrameBuffers& buffers, engine::MessageBus& bus, bool wait);
    const std::optional<plugin_msgs::SplatStatistics>& latest() const { return latest_; }

private:
    struct Readback {
        engine::gl::Buffer buffer{engine::gl::NoCreate};
        engine::gl::Fence fence;
        Frame frame;
    };
    std::array<Readback, 4> readbacks_;
    std::uint64_t frames_ = 0;
    std::optional<plugin_msgs::SplatStatistics> latest_;
};

}  // namespace splat_lod
