// Capture shapes and the cameras generated for them: detection on synthetic camera sets (an orbit
// ring, a forward-facing grid, cameras inside looking out), the grid, inside and rings specs and their
// errors, and the default forward direction.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "splat_lod/bake/bake_cameras.h"
#include "splat_lod/bake/capture_shape.h"

namespace {

using namespace splat_lod;
using bake::CaptureShape;

eval::CameraPose pose_towards(const glm::vec3& eye, const glm::vec3& direction) {
    eval::CameraPose pose;
    pose.eye = eye;
    pose.forward = glm::normalize(direction);
    pose.up = glm::normalize(glm::cross(glm::cross(pose.forward, glm::vec3(0, 1, 0)), pose.forward));
    pose.focus_distance = 1.0f;
    return pose;
}

eval::SceneExtent unit_scene() {
    return {glm::vec3(0.0f), 1.0f};
}

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const engine::Error& e) {
        return e.what();
    }
    return "";
}

// A hand-held sweep: eyes in a small box at z = 3 looking towards −z, turned a little.
std::vector<eval::CameraPose> forward_sweep() {
    std::vector<eval::CameraPose> poses;
    for (int i = 0; i < 12; ++i) {
        const float x = -0.5f + 0.1f * static_cast<float>(i), yaw = 0.15f * std::sin(static_cast<float>(i));
        poses.push_back(
            pose_towards({x, 0.2f * static_cast<float>(i % 3), 3.0f}, {std::sin(yaw), -0.1f, -std::cos(yaw)}));
    }
    return poses;
}

}  // namespace

TEST(CaptureShape, AnOrbitAroundTheSceneIsOrbit) {
    const auto detection = bake::detect_capture_shape(eval::orbit_poses(unit_scene(), {0, 1, 0}, 12), unit_scene());
    EXPECT_EQ(detection.shape, CaptureShape::orbit) << detection.reason;
    EXPECT_LT(detection.towards_centre_deg, 1.0f);
    EXPECT_EQ(detection.reason.rfind("orbit: ", 0), 0u) << detection.reason;
    const auto rings = bake::bake_camera_poses("rings:3x8", unit_scene(), {0, 1, 0});
    EXPECT_EQ(bake::detect_capture_shape(rings, unit_scene()).shape, CaptureShape::orbit);
    // Two opposite views (the evaluation's orbit:2) are an orbit too.
    EXPECT_EQ(bake::detect_capture_shape(eval::orbit_poses(unit_scene(), {0, 1, 0}, 2), unit_scene()).shape,
              CaptureShape::orbit);
}

TEST(CaptureShape, AForwardSweepFromOneSideIsForward) {
    const auto detection = bake::detect_capture_shape(forward_sweep(), unit_scene());
    EXPECT_EQ(detection.shape, CaptureShape::forward) << detection.reason;
    EXPECT_LT(detection.cone_deg, 15.0f);
    EXPECT_EQ(detection.one_side_fraction, 1.0f);
    EXPECT_NEAR(detection.mean_direction.z, -1.0f, 0.05f);
    EXPECT_NE(detection.reason.find("view directions within"), std::string::npos) << detection.reason;
    // The generated grid is a forward capture, also inside a room (eyes within the robust radius).
    bake::CameraPlacement placement;
    placement.extent = {glm::vec3(0.0f), 10.0f};
    const auto grid = bake::bake_camera_poses("grid:5x4", placement);
    EXPECT_EQ(bake::detect_capture_shape(grid, placement.extent).shape, CaptureShape::forward);
}

TEST(CaptureShape, CamerasInsideLookingOutAreWorld) {
    std::vector<eval::CameraPose> poses;
    for (int i = 0; i < 16; ++i) {
        const float a = 0.4f * static_cast<float>(i);
        const glm::vec3 out(std::cos(a), 0.0f, std::sin(a));
        poses.push_back(pose_towards(0.3f * static_cast<float>(i % 3) * out, out));
    }
    const auto detection = bake::detect_capture_shape(poses, unit_scene());
    EXPECT_EQ(detection.shape, CaptureShape::world) << detection.reason;
    EXPECT_EQ(detection.inside_fraction, 1.0f);
    const auto inside = bake::bake_camera_poses("inside:2x8", {glm::vec3(0.0f), 5.0f}, {0, 1, 0});
    EXPECT_EQ(inside.size(), 16u);
    EXPECT_EQ(bake::detect_capture_shape(inside, {glm::vec3(0.0f), 5.0f}).shape, CaptureShape::world);
}

TEST(CaptureShape, AWalkThroughTheSceneIsNotForward) {
    // All looking one way, but standing on both sides of the centre: a walk through a world.
    std::vector<eval::CameraPose> poses;
    for (int i = 0; i < 10; ++i) poses.push_back(pose_towards({0.0f, 0.0f, 0.6f - 0.16f * i}, {0.1f, 0.0f, -1.0f}));
    const auto detection = bake::detect_capture_shape(poses, unit_scene());
    EXPECT_NE(detection.shape, CaptureShape::forward) << detection.reason;
    EXPECT_EQ(detection.shape, CaptureShape::world) << detection.reason;
}

TEST(CaptureShape, NoCamerasOrNoRuleFallsBackToOrbitAndSaysSo) {
    EXPECT_EQ(bake::detect_capture_shape({}, unit_scene()).shape, CaptureShape::orbit);
    EXPECT_EQ(bake::detect_capture_shape({}, unit_scene()).reason, "orbit: no cameras");
    // Outside the scene, looking every way but at it.
    std::vector<eval::CameraPose> poses;
    for (int i = 0; i < 8; ++i) {
        const float a = 0.785f * static_cast<float>(i);
        const glm::vec3 out(std::cos(a), 0.0f, std::sin(a));
        poses.push_back(pose_towards(5.0f * out, glm::vec3(-out.z, 0.0f, out.x)));
    }
    const auto detection = bake::detect_capture_shape(poses, unit_scene());
    EXPECT_EQ(detection.shape, CaptureShape::orbit);
    EXPECT_EQ(detection.reason.rfind("orbit (no rule matched)", 0), 0u) << detection.reason;
}

TEST(CaptureShape, ParsesTheOptionAndNamesItInErrors) {
    EXPECT_FALSE(bake::parse_capture_shape("auto").has_value());
    EXPECT_EQ(bake::parse_capture_shape("orbit"), CaptureShape::orbit);
    EXPECT_EQ(bake::parse_capture_shape("forward"), CaptureShape::forward);
    EXPECT_EQ(bake::parse_capture_shape("world"), CaptureShape::world);
    const std::string message = error_of([] { bake::parse_capture_shape("sideways"); });
    EXPECT_NE(message.find("--capture"), std::string::npos) << message;
    EXPECT_NE(message.find("sideways"), std::string::npos) << message;
    EXPECT_STREQ(bake::capture_shape_name(CaptureShape::forward), "forward");
    EXPECT_EQ(bake::auto_camera_spec(CaptureShape::orbit), "rings:3x8");
    EXPECT_EQ(bake::auto_camera_spec(CaptureShape::forward), "grid:8x6x3");
    EXPECT_EQ(bake::generated_capture_shape("grid:2x2"), CaptureShape::forward);
    EXPECT_EQ(bake::generated_capture_shape("orbit:4"), CaptureShape::orbit);
    EXPECT_FALSE(bake::generated_capture_shape("cameras.json").has_value());
}

TEST(BakeGrid, EyesStandOnTheCaptureSideAndLookAlongForward) {
    // A box of points 4 wide, 2 high, 10 deep along −z.
    std::vector<glm::vec3> points;
    for (int i = 0; i <= 100; ++i)
        for (const float z : {-10.0f, -5.0f, 0.0f}) points.push_back({-2.0f + 0.04f * i, 0.02f * i, z});
    bake::CameraPlacement placement;
    placement.extent = eval::robust_extent(points);
    placement.positions = points;
    const auto poses = bake::bake_camera_poses("grid:5x4x3", placement);
    ASSERT_EQ(poses.size(), 60u);
    for (const auto& pose : poses) {
        EXPECT_LT(std::acos(-pose.forward.z), glm::radians(22.5f)) << pose.name;  // ±20° yaw, ±10° pitch
        EXPECT_NEAR(glm::length(pose.forward), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(pose.forward, pose.up), 0.0f, 1e-5f);
        EXPECT_GE(pose.eye.x, -1.0f - 1e-4f);  // the middle half of the width
        EXPECT_LE(pose.eye.x, 1.0f + 1e-4f);
        EXPECT_GE(pose.eye.y, 0.5f - 1e-3f);  // and of the height
        EXPECT_LE(pose.eye.y, 1.5f + 1e-3f);
        EXPECT_GT(pose.eye.z, -2.5f);  // the capture side: at most 24 % of the depth in
    }
    EXPECT_NEAR(poses.front().eye.z, 0.0f, 1e-3f);  // the first plane at the near side
    // Another forward direction turns the whole grid.
    placement.forward = {1.0f, 0.0f, 0.0f};
    for (const auto& pose : bake::bake_camera_poses("grid:2x2x1", placement)) EXPECT_GT(pose.forward.x, 0.92f);
}

TEST(BakeGrid, SpecErrorsNameTheSpecAndTheForm) {
    const bake::CameraPlacement placement;
    EXPECT_EQ(bake::bake_camera_poses("grid:1x1x1", placement).size(), 1u);
    EXPECT_EQ(bake::bake_camera_poses("grid:3x2", placement).size(), 12u);  // two depth planes by default
    for (const std::string spec : {"grid:", "grid:5", "grid:0x4", "grid:65x4", "grid:5x4x9", "grid:5x4x", "grid:5by4",
                                   "grid:-1x4", "grid:5x4x2x1", "grid:5x4 ", "grid:x4"}) {
        const std::string message = error_of([&] { bake::bake_camera_poses(spec, placement); });
        EXPECT_NE(message.find("\"" + spec + "\""), std::string::npos) << spec << ": " << message;
        EXPECT_NE(message.find("grid:CxR or grid:CxRxD"), std::string::npos) << spec << ": " << message;
    }
    EXPECT_NE(error_of([&] { bake::bake_camera_poses("inside:0x8", placement); }).find("inside:RxA"),
              std::string::npos);
    EXPECT_NE(error_of([&] { bake::bake_camera_poses("rings:3x8x1", placement); }).find("rings:RxA"),
              std::string::npos);
    bake::CameraPlacement up_forward;
    up_forward.forward = {0.0f, 2.0f, 0.0f};
    EXPECT_NE(error_of([&] { bake::bake_camera_poses("grid:2x2", up_forward); }).find("parallel to up"),
              std::string::npos);
}

TEST(BakeGrid, DefaultForwardIsTheViewOfACameraWithRightAlongX) {
    const glm::vec3 y_up = bake::default_forward({0, 1, 0}), y_down = bake::default_forward({0, -2, 0});
    EXPECT_NEAR(y_up.z, -1.0f, 1e-6f);
    EXPECT_NEAR(y_down.z, 1.0f, 1e-6f);
    EXPECT_NE(error_of([] { bake::default_forward({1, 0, 0}); }).find("--forward"), std::string::npos);
    EXPECT_NE(error_of([] { bake::default_forward({0, 0, 0}); }).find("up direction"), std::string::npos);
}

// A large capture, or a flat one of a million Gaussians, is pointed to a streamed world; a small or a
// thick one is not.
TEST(StreamedWorldAdvice, LargeOrFlatCapturesAreBetterAsAWorld) {
    SplatCloud cloud;
    cloud.resize(bake::kFlatCaptureGaussians);
    for (std::size_t i = 0; i < cloud.size(); ++i)  // 100 × 2 × 60 units: flat
        cloud.positions[i] = {static_cast<float>(i % 1000) * 0.1f, static_cast<float>(i % 7) * 0.3f,
                              static_cast<float>(i / 1000) * 0.06f};
    EXPECT_NE(bake::streamed_world_advice(cloud).find("flat capture"), std::string::npos);
    for (std::size_t i = 0; i < cloud.size(); ++i) cloud.positions[i].y *= 20.0f;  // 36 units thick
    EXPECT_EQ(bake::streamed_world_advice(cloud), "");
    cloud.resize(bake::kWorldCaptureGaussians);
    EXPECT_NE(bake::streamed_world_advice(cloud).find("2000000 Gaussians"), std::string::npos);
    SplatCloud small;
    small.resize(1000);
    for (std::size_t i = 0; i < small.size(); ++i) small.positions[i] = {static_cast<float>(i), 0.0f, 0.0f};
    EXPECT_EQ(bake::streamed_world_advice(small), "") << "a small capture, however flat, is one file";
}
