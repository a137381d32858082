#pragma once
// Named GPU time spans per frame from GL_TIMESTAMP queries, read back a few frames later only
// once the driver says they are available, so reading never stalls the frame.
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/gl/objects.h"

namespace engine::gl {

struct GpuSpan {
    std::string name;
    double milliseconds = 0.0;
};

// A frame's spans summed by name: a pass that runs a step more than once in a frame (the splat pass's
// strips) has a span per run.
std::map<std::string, double> span_totals(const std::vector<GpuSpan>& spans);

class GpuTimers {
public:
    // Frames whose queries may be outstanding before begin_frame() waits for the oldest. Drivers
    // throttle long before this; headless loops on a busy software rasteriser may not.
    static constexpr std::size_t max_frames_in_flight = 16;

    GpuTimers() = default;
    void begin_frame();
    // Starts and ends a named span; spans may nest.
    int begin(const std::string& name);
    void end(int span);
    void end_frame();

    // The newest frame whose queries have all completed (without waiting), if any.
    const std::optional<std::vector<GpuSpan>>& latest() const { return latest_; }
    // The frame number (counting begin_frame() calls from 0) that latest() was measured in.
    std::int64_t latest_frame() const { return latest_frame_; }
    // How often begin_frame() had to wait because max_frames_in_flight frames were outstanding.
    std::uint64_t frames_waited() const { return waited_; }
    // Blocks until every recorded frame is read; for tools and tests, never inside a frame loop.
    void wait_all();

private:
    struct Frame {
        std::vector<std::string> names;
        std::vector<Query> start, stop;
        std::size_t used = 0;
        std::uint64_t number = 0;
    };
    // Reads the frame's results; false when they are not available yet and `wait` is off.
    bool collect(Frame& frame, bool wait);
    // Gives `frame` the queries of `spans_` spans. Every frame holds as many (a new frame gets them,
    // and a frame with more spans than any before adds one to every frame), so that the query objects
    // depend on the most spans a frame has had, not on which frame objects served those frames.
    void fill(Frame& frame) const;
    void collect_ready();

    std::deque<std::unique_ptr<Frame>> pending_;  // oldest first; the driver completes them in order
    std::vector<std::unique_ptr<Frame>> free_;    // read, with their query objects kept for reuse
    std::unique_ptr<Frame> current_;
    std::uint64_t frame_counter_ = 0;
    std::uint64_t waited_ = 0;
    std::size_t spans_ = 0;  // the most spans a frame has had
    std::optional<std::vector<GpuSpan>> latest_;
    std::int64_t latest_frame_ = -1;
};

// RAII span: GpuTimerScope scope(timers, "mesh");
class GpuTimerScope {
public:
    GpuTimerScope(GpuTimers& timers, const std::string& name) : timers_(timers), span_(timers.begin(name)) {}
    ~GpuTimerScope() { timers_.end(span_); }
    GpuTimerScope(const GpuTimerScope&) = delete;
    GpuTimerScope& operator=(const GpuTimerScope&) = delete;

private:
    GpuTimers& timers_;
    int span_;
};

}  // namespace engine::gl
