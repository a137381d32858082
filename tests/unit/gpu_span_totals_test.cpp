// A frame's GPU spans summed by name (engine/gl/gpu_timers.h): a step run more than once in a frame
// counts once with its total, the others as they are.
#include <gtest/gtest.h>

#include "engine/gl/gpu_timers.h"

TEST(GpuSpanTotals, SpansOfOneNameSumAndOthersStay) {
    const std::vector<engine::gl::GpuSpan> spans{
        {"splat", 10.0}, {"splat.raster", 2.5}, {"mesh", 1.0}, {"splat.raster", 4.0}, {"splat.raster", 0.5}};
    const auto totals = engine::gl::span_totals(spans);
    ASSERT_EQ(totals.size(), 3u);
    EXPECT_DOUBLE_EQ(totals.at("splat.raster"), 7.0);
    EXPECT_DOUBLE_EQ(totals.at("splat"), 10.0);
    EXPECT_DOUBLE_EQ(totals.at("mesh"), 1.0);
    EXPECT_TRUE(engine::gl::span_totals({}).empty());
}
