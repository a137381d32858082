#include "engine/gl/gpu_timers.h"

#include "engine/core/error.h"

namespace engine::gl {

bool GpuTimers::try_collect(Frame& frame, bool wait) {
    if (!frame.pending) return true;
    if (frame.used > 0) {
        GLint available = GL_FALSE;
        const GLuint last = frame.stop[frame.used - 1].id();
        if (!wait) {
            glGetQueryObjectiv(last, GL_QUERY_RESULT_AVAILABLE, &available);
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
    }
    frame.pending = false;
    return true;
}

void GpuTimers::begin_frame() {
    current_ = static_cast<int>(frame_counter_ % frames_in_flight);
    Frame& frame = frames_[current_];
    // Collect every older frame that is ready, oldest first.
    for (int k = 1; k <= frames_in_flight; ++k) {
        Frame& older = frames_[(current_ + k) % frames_in_flight];
        if (&older != &frame) try_collect(older, false);
    }
    if (frame.pending && !try_collect(frame, false)) ++dropped_;  // reuse without waiting
    frame.pending = false;
    frame.used = 0;
    frame.number = frame_counter_;
    frame.names.clear();
}

int GpuTimers::begin(const std::string& name) {
    if (current_ < 0) fail("engine::gl::GpuTimers::begin(): called outside begin_frame()/end_frame()");
    Frame& frame = frames_[current_];
    if (frame.used == frame.start.size()) {
        frame.start.emplace_back(GL_TIMESTAMP, "timer start " + name);
        frame.stop.emplace_back(GL_TIMESTAMP, "timer stop " + name);
    }
    frame.names.push_back(name);
    glQueryCounter(frame.start[frame.used].id(), GL_TIMESTAMP);
    return static_cast<int>(frame.used++);
}

void GpuTimers::end(int span) {
    Frame& frame = frames_[current_];
    glQueryCounter(frame.stop[static_cast<std::size_t>(span)].id(), GL_TIMESTAMP);
}

void GpuTimers::end_frame() {
    // Submit the frame's commands so its queries can complete while the CPU moves on (a window's
    // buffer swap does this too; headless frames have no swap).
    glFlush();
    frames_[current_].pending = true;
    ++frame_counter_;
    current_ = -1;
}

void GpuTimers::wait_all() {
    for (int k = 1; k <= frames_in_flight; ++k) {
        try_collect(frames_[(static_cast<int>(frame_counter_ % frames_in_flight) + k - 1) % frames_in_flight], true);
    }
}

}  // namespace engine::gl
