#pragma once
// Where the camera is this frame, for plugins that stream or select by distance.
#include <array>
#include <cstdint>
#include <string_view>

#include <nlohmann/json.hpp>

namespace plugin_msgs {

struct CameraState {
    static constexpr std::string_view kind = "camera_state";

    std::uint64_t frame_index = 0;
    std::array<float, 3> position{0, 0, 0};
    std::array<float, 3> forward{0, 0, -1};
    std::array<float, 3> up{0, 1, 0};
    float fov_y_deg = 50.0f;
    float znear = 0.1f;
    float zfar = 1000.0f;
    int width = 0;
    int height = 0;

    friend bool operator==(const CameraState&, const CameraState&) = default;
};

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(CameraState, frame_index, position, forward, up, fov_y_deg, znear, zfar,
                                                width, height)

}  // namespace plugin_msgs
