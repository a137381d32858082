// A forward-facing bake of a tiny room (floor, far wall and side walls of small chequered Gaussians):
// the generated grid is detected as a forward capture, the forward settings bake, and on views off the
// grid the `full` selection keeps the fine level near and the coarse levels far; the members' cap and
// the thickening do what the stage headers (ranges.h, pooling.h) say.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bake_steps.h"
#include "splat_lod/bake/bake.h"
#include "splat_lod/bake/bake_cameras.h"
#include "splat_lod/bake/capture_shape.h"
#include "splat_lod/core/lod_selection.h"

namespace {

using namespace splat_lod;

// Flat Gaussians `step` apart on the rectangle corner + [0, 1]·u + [0, 1]·v, chequered every tile.
void add_wall(SplatCloud& cloud, glm::vec3 corner, glm::vec3 u, glm::vec3 v, float step) {
    const int nu = static_cast<int>(glm::length(u) / step), nv = static_cast<int>(glm::length(v) / step);
    const glm::vec3 normal = glm::normalize(glm::cross(u, v));
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const std::size_t k = cloud.size();
            cloud.resize(k + 1);
            cloud.positions[k] = corner + u * ((i + 0.5f) / nu) + v * ((j + 0.5f) / nv);
            // The thin axis along the normal: the identity rotation when the normal is z, else a quarter turn.
            const float h = std::sqrt(0.5f);
            cloud.rotations[k] = std::abs(normal.z) > 0.5f   ? Rotation{1, 0, 0, 0}
                                 : std::abs(normal.x) > 0.5f ? Rotation{h, 0, h, 0}
                                                             : Rotation{h, h, 0, 0};
            cloud.log_scales[k] = glm::log(glm::vec3(0.6f * step, 0.6f * step, 0.05f * step));
            cloud.opacity_logits[k] = 4.0f;
            const glm::vec3 rgb = (i + j) % 2 ? glm::vec3(0.9f, 0.8f, 0.3f) : glm::vec3(0.1f, 0.2f, 0.6f);
            cloud.sh_dc[k] = (rgb - 0.5f) / kShC0;
        }
}

SplatCloud tiny_room() {
    SplatCloud cloud;
    const float step = 0.08f;
    add_wall(cloud, {-1.5f, 0.0f, 0.5f}, {3.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -4.5f}, step);  // floor
    add_wall(cloud, {-1.5f, 0.0f, -4.0f}, {3.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f}, step);  // far wall
    add_wall(cloud, {-1.5f, 0.0f, -4.0f}, {0.0f, 2.0f, 0.0f}, {0.0f, 0.0f, 4.5f}, step);  // left wall
    add_wall(cloud, {1.5f, 0.0f, -4.0f}, {0.0f, 0.0f, 4.5f}, {0.0f, 2.0f, 0.0f}, step);   // right wall
    return cloud;
}

struct Drawn {
    std::size_t fine = 0, coarse = 0;
};

// What `full` draws (centres inside the image) in a camera at render scale k.
Drawn drawn(const SplatCloud& cloud, const reference::ReferenceCamera& camera, int k) {
    const auto scaled = bake::detail::scaled_camera(camera, k);
    LodRule rule;
    rule.mode = plugin_msgs::LodMode::full;
    Drawn out;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const double s = bake::detail::coverage_in_camera(cloud, i, scaled, 0.2);
        if (s < 0.0 || !lod_selected(rule, cloud.lod_level[i], s, cloud.coverage_min[i], cloud.coverage_max[i]))
            continue;
        (cloud.lod_level[i] == 1 ? out.fine : out.coarse) += 1;
    }
    return out;
}

}  // namespace

TEST(BakeForward, ATinyRoomBakesForItsForwardGrid) {
    const SplatCloud fine = tiny_room();
    bake::CameraPlacement placement;
    placement.extent = eval::robust_extent(fine.positions);
    placement.positions = fine.positions;
    const auto poses = bake::bake_camera_poses("grid:3x2", placement);
    ASSERT_EQ(poses.size(), 12u);
    const auto detection = bake::detect_capture_shape(poses, placement.extent);
    ASSERT_EQ(detection.shape, bake::CaptureShape::forward) << detection.reason;
    bake::BakeOptions options = bake::capture_defaults({}, detection.shape);
    EXPECT_EQ(options.pooling, bake::PoolingRule::moments);
    EXPECT_TRUE(options.member_ranges);
    options.refine_iterations = 20;
    options.threads = 2;
    bake::BakeSummary summary;
    const SplatCloud baked = bake::bake_lod(fine, bake::bake_cameras(poses, 128, 128), options, &summary);
    ASSERT_EQ(summary.levels.size(), 3u);
    EXPECT_EQ(baked.level_handover, splat_lod::LevelHandover::abutting) << "member ranges: levels meet at one coverage";
    for (const auto& level : summary.levels) EXPECT_GT(level.added, 0u) << "level " << level.level;

    // Views off the grid: between its eyes and a step into the room, turned a little.
    const auto base = bake::bake_camera_poses("grid:2x2x1", placement);
    for (const auto& pose : base) {
        eval::CameraPose view = pose;
        view.eye += glm::vec3(0.1f, 0.05f, -0.3f);
        const auto camera = reference::make_reference_camera(eval::make_view(view, 128, 128));
        const Drawn near = drawn(baked, camera, 1), far = drawn(baked, camera, 16);
        // Near, the fine level serves the view; far, the coarse levels do.
        EXPECT_LE(near.coarse * 100, near.fine) << pose.name << ": " << near.coarse << " coarse at 1x";
        EXPECT_GT(far.coarse, far.fine) << pose.name;
    }
}

TEST(BakeForward, ThickenRaisesThinAxesOnly) {
    SplatCloud cloud;
    cloud.resize(1);
    cloud.log_scales[0] = glm::log(glm::vec3(0.1f, 0.05f, 0.001f));
    bake::detail::thicken(cloud, 0, 0.3);
    EXPECT_NEAR(std::exp(cloud.log_scales[0].x), 0.1f, 1e-6f);
    EXPECT_NEAR(std::exp(cloud.log_scales[0].y), 0.05f, 1e-6f);
    EXPECT_NEAR(std::exp(cloud.log_scales[0].z), 0.03f, 1e-6f);
    bake::detail::thicken(cloud, 0, 0.0);  // off
    EXPECT_NEAR(std::exp(cloud.log_scales[0].z), 0.03f, 1e-6f);
}

TEST(BakeForward, MemberCapIsWhereTheMembersStopBeingDrawn) {
    // The coarse Gaussian is twice its median member in both cameras that see it (r = 2); its members
    // stop being drawn at max(S_T, 0.5 · coverage_min) = max(2, 3) = 3 px, so the cap is 2 · 3 / 1.5.
    const std::vector<float> coarse = {16.0f, 8.0f, -1.0f};
    const std::vector<float> a = {8.0f, 4.0f, 5.0f}, b = {6.0f, 4.0f, 5.0f}, c = {10.0f, -1.0f, 5.0f};
    const std::vector<std::span<const float>> members = {a, b, c};
    const std::vector<float> minima = {6.0f, 6.0f, 6.0f};
    const bake::BakeOptions options;
    EXPECT_NEAR(bake::detail::member_cap(coarse, members, minima, options), 2.0 * 3.0 / 1.5, 1e-9);
    // Members without a range stop at S_T: the cap is 2 · 2 / 1.5.
    const std::vector<float> unset = {-1.0f, -1.0f, -1.0f};
    EXPECT_NEAR(bake::detail::member_cap(coarse, members, unset, options), 2.0 * 2.0 / 1.5, 1e-9);
    // Not seen with a member: no cap.
    const std::vector<float> alone = {-1.0f, -1.0f, 4.0f};
    const std::vector<float> hidden = {-1.0f, -1.0f, -1.0f};
    const std::vector<std::span<const float>> hidden_members = {hidden};
    EXPECT_EQ(bake::detail::member_cap(alone, hidden_members, minima, options), -1.0);
}
