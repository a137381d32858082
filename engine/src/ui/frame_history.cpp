#include "engine/ui/frame_history.h"

#include <algorithm>
#include <numeric>

namespace engine {
namespace {

const plugin_msgs::PassTiming* find_pass(const plugin_msgs::FrameStatistics& frame, const std::string& name) {
    for (const auto& pass : frame.passes)
        if (pass.name == name) return &pass;
    return nullptr;
}

}  // namespace

void FrameHistory::push(const plugin_msgs::FrameStatistics& frame) {
    frames_.push_back(frame);
    while (frames_.size() > capacity_) frames_.pop_front();
}

std::vector<float> FrameHistory::cpu_frame_ms() const {
    std::vector<float> out;
    out.reserve(frames_.size());
    for (const auto& frame : frames_) out.push_back(static_cast<float>(frame.cpu_frame_ms));
    return out;
}

std::vector<std::string> FrameHistory::pass_names() const {
    std::vector<std::string> names;
    for (auto frame = frames_.rbegin(); frame != frames_.rend(); ++frame)
        for (const auto& pass : frame->passes)
            if (std::find(names.begin(), names.end(), pass.name) == names.end()) names.push_back(pass.name);
    return names;
}

std::vector<float> FrameHistory::pass_cpu_ms(const std::string& pass) const {
    std::vector<float> out;
    for (const auto& frame : frames_)
        if (const auto* timing = find_pass(frame, pass)) out.push_back(static_cast<float>(timing->cpu_ms));
    return out;
}

std::vector<float> FrameHistory::pass_gpu_ms(const std::string& pass) const {
    std::vector<float> out;
    for (const auto& frame : frames_) {
        const auto* timing = find_pass(frame, pass);
        if (timing != nullptr && timing->gpu_ms >= 0.0) out.push_back(static_cast<float>(timing->gpu_ms));
    }
    return out;
}

float FrameHistory::mean(const std::vector<float>& values) {
    if (values.empty()) return 0.0f;
    return std::accumulate(values.begin(), values.end(), 0.0f) / static_cast<float>(values.size());
}

float FrameHistory::max(const std::vector<float>& values) {
    if (values.empty()) return 0.0f;
    return *std::max_element(values.begin(), values.end());
}

}  // namespace engine
