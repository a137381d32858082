#pragma once
// Progress lines of the long headless runs (profile, reference): one line per step at most every
// two seconds (and always the last), with the time per step and what is left:
//   "sample_game_harness: reference frame 3/12 (canopy), 41.20 s each, 2m04s elapsed, ETA 6m11s"
#include <chrono>
#include <cstdio>
#include <string>

namespace sample_game {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start);
std::string duration(double seconds);  // "42s", "3m07s"

class Progress {
public:
    // `out` may be null (no lines); total 0: open-ended (no ETA).
    Progress(std::FILE* out, std::string stage, std::size_t total)
        : out_(out), stage_(std::move(stage)), total_(total) {}
    void step(std::size_t done, const std::string& detail);

private:
    std::FILE* out_;
    std::string stage_;
    std::size_t total_;
    Clock::time_point start_ = Clock::now(), last_{};
};

}  // namespace sample_game
