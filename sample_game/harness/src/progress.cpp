#include "progress.h"

#include <algorithm>

namespace sample_game {

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string duration(double seconds) {
    const auto s = static_cast<long long>(std::max(0.0, seconds) + 0.5);
    char text[32];
    if (s >= 60)
        std::snprintf(text, sizeof text, "%lldm%02llds", s / 60, s % 60);
    else
        std::snprintf(text, sizeof text, "%llds", s);
    return text;
}

void Progress::step(std::size_t done, const std::string& detail) {
    if (!out_ || (done == 0 && total_ > 0)) return;
    const auto now = Clock::now();
    if ((total_ == 0 || done < total_) && now - last_ < std::chrono::seconds(2)) return;
    last_ = now;
    const double elapsed = seconds_since(start_);
    if (total_ == 0) {  // open-ended: no ETA
        std::fprintf(out_, "sample_game_harness: %s %zu%s, %s elapsed\n", stage_.c_str(), done, detail.c_str(),
                     duration(elapsed).c_str());
        std::fflush(out_);
        return;
    }
    const double per = done > 0 ? elapsed / static_cast<double>(done) : 0.0;
    std::fprintf(out_, "sample_game_harness: %s %zu/%zu%s, %.2f s each, %s elapsed, ETA %s\n", stage_.c_str(), done,
                 total_, detail.c_str(), per, duration(elapsed).c_str(),
                 duration(per * static_cast<double>(total_ - done)).c_str());
    std::fflush(out_);
}

}  // namespace sample_game
