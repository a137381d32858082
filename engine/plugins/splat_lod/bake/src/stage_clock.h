#pragma once
// Internal to the bake: each stage's wall time into the summary and its progress to the caller.
#include <algorithm>
#include <chrono>
#include <string>

#include "splat_lod/bake/bake.h"

namespace splat_lod::bake::detail {

class StageClock {
public:
    StageClock(BakeSummary& summary, const BakeOptions& options) : summary_(summary), options_(options) {}
    void start(const std::string& stage) {
        stop();
        stage_ = stage;
        begin_ = std::chrono::steady_clock::now();
        report(0.0);
    }
    void report(double fraction) const {
        if (options_.progress && !stage_.empty()) options_.progress(stage_, std::clamp(fraction, 0.0, 1.0));
    }
    void stop() {
        if (stage_.empty()) return;
        report(1.0);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
        summary_.stages.push_back({stage_, seconds});
        stage_.clear();
    }

private:
    BakeSummary& summary_;
    const BakeOptions& options_;
    std::string stage_;
    std::chrono::steady_clock::time_point begin_;
};

}  // namespace splat_lod::bake::detail
