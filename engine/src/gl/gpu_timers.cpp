#include "engine/gl/gpu_timers.h"

#include <string>

#include "engine/core/error.h"

namespace engine::gl {

bool GpuTimers::collect(Frame& frame, bool wait) {
    if (frame.used == 0) return true;
    if (!wait) {
        GLint available = GL_FALSE;
        glGetQueryObjectiv(frame.stop[frame.used - 1].id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (available != GL_TRUE) return false;
    }
    std::vector<GpuSpan> spans;
    spans.reserve(frame.used);
    for (std::size_t i = 0; i < frame.used; ++i) {
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(frame.start[i].id(), GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(frame.stop[i].id(), GL_QUERY_RESULT, &t1);
        spans.push_back({frame.names[i], t1 >= t0 ? static_cast<double>(t1 - t0) * 1e-6 : 0.0});
    }
    latest_ = std::move(spans);
    latest_frame_ = static_cast<std::int64_t>(frame.number);
    return true;
}

// Reads every finished frame, oldest first, stopping at the first one still running.
void GpuTimers::collect_ready() {
    while (!pending_.empty() && collect(*pending_.front(), false)) {
        free_.push_back(std::move(pending_.front()));
        pending_.pop_front();
    }
}

void GpuTimers::begin_frame() {
    collect_ready();
    if (pending_.size() >= max_frames_in_flight) {
        collect(*pending_.front(), true);  // bounded: the GPU is this many frames behind
        free_.push_back(std::move(pending_.front()));
        pending_.pop_front();
        ++waited_;
    }
    if (free_.empty()) {
        current_ = std::make_unique<Frame>();
        fill(*current_);
    } else {
        current_ = std::move(free_.back());
        free_.pop_back();
    }
    current_->used = 0;
    current_->number = frame_counter_;
    current_->names.clear();
}

int GpuTimers::begin(const std::string& name) {
    if (!current_) fail("engine::gl::GpuTimers::begin(): called outside begin_frame()/end_frame()");
    Frame& frame = *current_;
    if (frame.used == spans_) {
        ++spans_;
        fill(frame);
        for (auto& f : pending_) fill(*f);
        for (auto& f : free_) fill(*f);
    }
    frame.names.push_back(name);
    glQueryCounter(frame.start[frame.used].id(), GL_TIMESTAMP);
    return static_cast<int>(frame.used++);
}

void GpuTimers::fill(Frame& frame) const {
    while (frame.start.size() < spans_) {
        const std::string number = std::to_string(frame.start.size());
        frame.start.emplace_back(GL_TIMESTAMP, "timer start " + number);
        frame.stop.emplace_back(GL_TIMESTAMP, "timer stop " + number);
    }
}

void GpuTimers::end(int span) {
    glQueryCounter(current_->stop[static_cast<std::size_t>(span)].id(), GL_TIMESTAMP);
}

void GpuTimers::end_frame() {
    // Submit the frame's commands so its queries can complete while the CPU moves on (a window's
    // buffer swap does this too; headless frames have no swap).
    glFlush();
    pending_.push_back(std::move(current_));
    ++frame_counter_;
}

std::map<std::string, double> span_totals(const std::vector<GpuSpan>& spans) {
    std::map<std::string, double> totals;
    for (const GpuSpan& span : spans) totals[span.name] += span.milliseconds;
    return totals;
}

void GpuTimers::wait_all() {
    while (!pending_.empty()) {
        collect(*pending_.front(), true);
        free_.push_back(std::move(pending_.front()));
        pending_.pop_front();
    }
}

}  // namespace engine::gl
