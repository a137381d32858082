#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/render/camera.h"
#include "engine/scene/transform.h"
#include "engine/ui/fly_camera.h"

using engine::FlyCamera;
using engine::FlyCameraInput;

namespace {

void expect_near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-4f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

glm::vec3 column(const glm::mat4& m, int i) {
    return glm::vec3(m[i]);
}

}  // namespace

TEST(FlyCamera, DefaultLooksDownMinusZWithYUp) {
    const FlyCamera camera;
    const glm::mat4 m = camera.camera_to_world();
    expect_near(column(m, 0), {1, 0, 0});
    expect_near(column(m, 1), {0, 1, 0});
    expect_near(column(m, 2), {0, 0, 1});
    expect_near(camera.forward(), {0, 0, -1});
}

TEST(FlyCamera, MatrixIsOrthonormalAndRightHanded) {
    FlyCamera camera;
    camera.look_at({1, 2, 3}, {-4, 0.5f, 7});
    const glm::mat4 m = camera.camera_to_world();
    EXPECT_NEAR(glm::determinant(glm::mat3(m)), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(column(m, 0), column(m, 1)), 0.0f, 1e-5f);
    EXPECT_NEAR(column(m, 0).y, 0.0f, 1e-6f);  // horizon stays level
    expect_near(column(m, 3), {1, 2, 3});
}

TEST(FlyCamera, LookAtPointsAtTheTarget) {
    FlyCamera camera;
    camera.look_at({0, 1, 5}, {0, 0, 0});
    const glm::mat4 m = camera.camera_to_world();
    const engine::CameraView view = engine::make_camera(m, 0.8f, 100, 100, 0.1f, 100.0f);
    const glm::vec3 p = view.project_to_pixel({0, 0, 0});
    EXPECT_NEAR(p.x, 50.0f, 1e-3f);
    EXPECT_NEAR(p.y, 50.0f, 1e-3f);
    EXPECT_GT(p.z, 0.0f);
}

TEST(FlyCamera, StartsFromAMatrixWithTheSameViewDirection) {
    engine::Transform t;
    t.translation = {3, 2, 1};
    t.rotation = engine::Transform::look_rotation({3, 2, 1}, {0, 0, -4}, {0, 1, 0});
    const FlyCamera camera(t.matrix());
    expect_near(camera.position(), {3, 2, 1});
    expect_near(camera.forward(), glm::normalize(glm::vec3(0, 0, -4) - glm::vec3(3, 2, 1)));
}

TEST(FlyCamera, StraightDownKeepsTheHeadingOfTheUpVector) {
    // Camera looking along −Y whose up vector points along −Z: its heading is −Z (yaw 0).
    glm::mat4 m(1.0f);
    m[0] = {1, 0, 0, 0};
    m[1] = {0, 0, -1, 0};
    m[2] = {0, 1, 0, 0};
    const FlyCamera camera(m);
    EXPECT_NEAR(camera.yaw(), 0.0f, 1e-3f);
    EXPECT_LT(camera.pitch(), -1.5f);
    EXPECT_FALSE(std::isnan(camera.camera_to_world()[0][0]));
}

TEST(FlyCamera, WasdMovesRelativeToTheView) {
    FlyCamera camera;  // at the origin, looking down −Z
    camera.speed = 2.0f;
    FlyCameraInput input;
    input.forward = true;
    camera.update(input, 0.5f);
    expect_near(camera.position(), {0, 0, -1});
    input = {};
    input.right = true;
    camera.update(input, 0.5f);
    expect_near(camera.position(), {1, 0, -1});
    input = {};
    input.up = true;
    input.fast = true;
    camera.update(input, 0.5f);
    expect_near(camera.position(), {1, 4, -1});
}

TEST(FlyCamera, DiagonalMovementIsNotFaster) {
    FlyCamera camera;
    FlyCameraInput input;
    input.forward = true;
    input.left = true;
    camera.update(input, 1.0f);
    EXPECT_NEAR(glm::length(camera.position()), camera.speed, 1e-4f);
}

TEST(FlyCamera, MouseTurnsOnlyWhileLooking) {
    FlyCamera camera;
    FlyCameraInput input;
    input.mouse_delta = {100, 0};
    camera.update(input, 0.016f);
    EXPECT_FLOAT_EQ(camera.yaw(), 0.0f);
    input.look = true;
    camera.update(input, 0.016f);
    EXPECT_GT(camera.forward().x, 0.1f);  // mouse right turns right (+X)
    input.mouse_delta = {0, 100};
    camera.update(input, 0.016f);
    EXPECT_LT(camera.forward().y, -0.1f);  // mouse down looks down
}

TEST(FlyCamera, PitchIsClampedShortOfVertical) {
    FlyCamera camera;
    FlyCameraInput input;
    input.look = true;
    input.mouse_delta = {0, -100000};
    camera.update(input, 0.016f);
    EXPECT_LT(camera.pitch(), 1.5708f);
    EXPECT_GT(camera.forward().y, 0.99f);
    EXPECT_FALSE(std::isnan(camera.camera_to_world()[0][0]));
}

TEST(FlyCamera, ScrollScalesTheSpeed) {
    FlyCamera camera;
    const float before = camera.speed;
    FlyCameraInput input;
    input.scroll = 2.0f;
    camera.update(input, 0.0f);
    EXPECT_NEAR(camera.speed, before * 1.44f, 1e-4f);
}
