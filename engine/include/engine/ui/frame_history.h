#pragma once
// The last N plugin_msgs::FrameStatistics, turned into the series the frame-time panel plots.
// GPU times arrive a few frames late and are −1 until then; series skip those gaps rather
// than plotting them as zero. GL-free, so the overlay's numbers are unit-tested.
#include <cstddef>
#include <deque>
#include <string>
#include <vector>

#include <plugin_msgs/frame_statistics.h>

namespace engine {

class FrameHistory {
public:
    explicit FrameHistory(std::size_t capacity = 240) : capacity_(capacity == 0 ? 1 : capacity) {}

    void push(const plugin_msgs::FrameStatistics& frame);
    void clear() { frames_.clear(); }

    std::size_t size() const { return frames_.size(); }
    std::size_t capacity() const { return capacity_; }
    const std::deque<plugin_msgs::FrameStatistics>& frames() const { return frames_; }

    std::vector<float> cpu_frame_ms() const;  // oldest first
    // Pass names in the order of the newest frame, then any older ones no longer present.
    std::vector<std::string> pass_names() const;
    std::vector<float> pass_cpu_ms(const std::string& pass) const;
    std::vector<float> pass_gpu_ms(const std::string& pass) const;  // measured values only

    static float mean(const std::vector<float>& values);  // 0 for an empty series
    static float max(const std::vector<float>& values);   // 0 for an empty series

private:
    std::size_t capacity_;
    std::deque<plugin_msgs::FrameStatistics> frames_;
};

}  // namespace engine
