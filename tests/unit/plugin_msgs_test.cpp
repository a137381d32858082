#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "message_test_helpers.h"
#include "plugin_msgs/plugin_msgs.h"

using nlohmann::json;
using namespace plugin_msgs;

using engine::test::expect_rejected;
using engine::test::expect_round_trip;
using engine::test::parse_error;

TEST(PluginMsgs, KindsAreDistinct) {
    const std::vector<std::string_view> kinds{CameraState::kind, FrameStatistics::kind, BackgroundWork::kind};
    for (std::size_t i = 0; i < kinds.size(); ++i)
        for (std::size_t j = i + 1; j < kinds.size(); ++j) EXPECT_NE(kinds[i], kinds[j]);
}

TEST(PluginMsgs, CameraStateRoundTrips) {
    CameraState camera;
    camera.frame_index = 12345678901234ull;
    camera.position = {1.5f, -2.25f, 1e-7f};
    camera.forward = {0.0f, 0.70710677f, -0.70710677f};
    camera.fov_y_deg = 63.3f;
    camera.width = 1920;
    camera.height = 1080;
    expect_round_trip(camera);
}

TEST(PluginMsgs, FrameStatisticsRoundTrips) {
    FrameStatistics stats;
    stats.frame_index = 42;
    stats.gpu_frame_index = 39;
    stats.width = 640;
    stats.height = 360;
    stats.cpu_frame_ms = 16.6666;
    stats.passes = {{"mesh", 1.25, 0.5}, {"splat_lod.raster", 3.0, -1.0}};
    expect_round_trip(stats);
    expect_round_trip(FrameStatistics{});
}

TEST(PluginMsgs, BackgroundWorkRoundTripsAndRejectsWhatIsNotAList) {
    expect_round_trip(BackgroundWork{"splat_lod", 7, {"baking scene.ply: 42 %", "importing park.ply: chunks 3 %"}});
    expect_round_trip(BackgroundWork{});
    expect_rejected<BackgroundWork>({{R"({"lines": "baking"})", "background_work.lines"},
                                     {R"({"frame_index": -1})", "background_work.frame_index"},
                                     {R"({"job": 1})", "background_work"}});
}
