#pragma once
// Per-frame timings the renderer publishes. GPU times arrive a few frames late (timer queries
// are read without stalling); `gpu_frame_index` says which frame they belong to.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace plugin_msgs {

struct PassTiming {
    std::string name;
    double cpu_ms = 0.0;
    double gpu_ms = -1.0;  // −1 while not yet available

    friend bool operator==(const PassTiming&, const PassTiming&) = default;
};

struct FrameStatistics {
    static constexpr std::string_view kind = "frame_statistics";

    std::uint64_t frame_index = 0;
    std::int64_t gpu_frame_index = -1;  // frame the gpu_ms values were measured in, −1 if none yet
    int width = 0;
    int height = 0;
    double cpu_frame_ms = 0.0;
    std::vector<PassTiming> passes;

    friend bool operator==(const FrameStatistics&, const FrameStatistics&) = default;
};

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PassTiming, name, cpu_ms, gpu_ms)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(FrameStatistics, frame_index, gpu_frame_index, width, height,
                                                cpu_frame_ms, passes)

}  // namespace plugin_msgs
