#include <gtest/gtest.h>

#include "engine/ui/frame_history.h"

using engine::FrameHistory;
using plugin_msgs::FrameStatistics;
using plugin_msgs::PassTiming;

namespace {

FrameStatistics frame(std::uint64_t index, double cpu_ms, std::vector<PassTiming> passes) {
    FrameStatistics f;
    f.frame_index = index;
    f.cpu_frame_ms = cpu_ms;
    f.passes = std::move(passes);
    return f;
}

}  // namespace

TEST(FrameHistory, KeepsTheLastCapacityFramesOldestFirst) {
    FrameHistory history(3);
    for (int i = 0; i < 5; ++i) history.push(frame(static_cast<std::uint64_t>(i), i * 1.0, {}));
    EXPECT_EQ(history.size(), 3u);
    EXPECT_EQ(history.cpu_frame_ms(), (std::vector<float>{2, 3, 4}));
    EXPECT_EQ(history.frames().front().frame_index, 2u);
}

TEST(FrameHistory, GpuSeriesSkipsFramesNotYetMeasured) {
    FrameHistory history;
    history.push(frame(0, 5, {{"mesh", 1.0, -1.0}}));
    history.push(frame(1, 5, {{"mesh", 2.0, -1.0}}));
    history.push(frame(2, 5, {{"mesh", 3.0, 0.5}}));
    EXPECT_EQ(history.pass_cpu_ms("mesh"), (std::vector<float>{1, 2, 3}));
    EXPECT_EQ(history.pass_gpu_ms("mesh"), (std::vector<float>{0.5f}));
    EXPECT_FLOAT_EQ(FrameHistory::mean(history.pass_cpu_ms("mesh")), 2.0f);
}

TEST(FrameHistory, PassNamesFollowTheNewestFrameThenOlderOnes) {
    FrameHistory history;
    history.push(frame(0, 1, {{"mesh", 1, -1}, {"old", 1, -1}}));
    history.push(frame(1, 1, {{"splats", 1, -1}, {"mesh", 1, -1}}));
    EXPECT_EQ(history.pass_names(), (std::vector<std::string>{"splats", "mesh", "old"}));
    EXPECT_TRUE(history.pass_cpu_ms("missing").empty());
}

TEST(FrameHistory, EmptySeriesStatisticsAreZero) {
    EXPECT_EQ(FrameHistory::mean({}), 0.0f);
    EXPECT_EQ(FrameHistory::max({}), 0.0f);
    EXPECT_EQ(FrameHistory(0).capacity(), 1u);
}
