#include "sample_game/world_path.h"

#include <algorithm>
#include <cmath>

namespace sample_game {
namespace {

constexpr float kPi = 3.14159265358979f;

glm::vec3 on_path(const WorldGround& t, float x, float above) {
    const float z = t.path_z(x);
    return {x, t.height(x, z) + above, z};
}

// Along the path at x, tilted down by `down` (a slope: 0 level, 1 at 45°).
glm::vec3 along_path(const WorldGround& t, float x, float down) {
    const glm::vec2 d = t.path_direction(x);
    return glm::normalize(glm::vec3(d.x, -down, d.y));
}

glm::vec3 horizontal(float angle) {
    return {std::cos(angle), 0.0f, std::sin(angle)};
}

}  // namespace

glm::vec3 world_centre(const WorldGround& ground) {
    return ground.centre();
}

WorldPathShape path_shape_for(const WorldGround& ground) {
    WorldPathShape shape;
    if (!ground.imported()) return shape;
    // A capture's unit is unknown: heights follow its scale, and never less than a small share of the
    // world (an aerial capture has no detail at eye height: its "walk" is a low pass over it).
    const float s = ground.scale(), size = ground.size();
    shape.eye_height_m = std::max(shape.eye_height_m * s, 0.005f * size);
    shape.canopy_height_m = std::max(shape.canopy_height_m * s, 0.03f * size);
    shape.min_clearance_m *= s;
    return shape;
}

std::vector<PathKey> make_world_path_keys(const WorldGround& t, const WorldPathShape& shape) {
    const float size = t.size();
    const WalkLengths len = walk_lengths(t);
    const float x0 = t.walk_start();
    const float eye = shape.eye_height_m, canopy = shape.canopy_height_m;
    std::vector<PathKey> keys;
    auto add = [&keys](const glm::vec3& position, const glm::vec3& look, Segment segment) {
        keys.push_back({position, look, segment});
    };
    // Ground: a walk along the path, looking ahead and slightly down (keys every ~10 m or closer, so
    // the spline follows the path's bends; sample_world_path() keeps the eye at walking height).
    const int walk_keys = std::clamp(static_cast<int>(len.walk / 10.0f), 3, 9);
    for (int j = 0; j < walk_keys; ++j) {
        const float x = x0 + len.walk * static_cast<float>(j) / static_cast<float>(walk_keys);
        add(on_path(t, x, eye), along_path(t, x, 0.05f), Segment::ground);
    }
    // Canopy: up over the path to the tree tops and on along it.
    const float x_top = x0 + len.walk;
    add(on_path(t, x_top, eye), along_path(t, x_top, 0.05f), Segment::canopy);
    add(on_path(t, x_top + 0.5f * len.canopy, eye + 0.55f * (canopy - eye)),
        along_path(t, x_top + 0.5f * len.canopy, 0.15f), Segment::canopy);
    add(on_path(t, x_top + len.canopy, canopy), along_path(t, x_top + len.canopy, 0.3f), Segment::canopy);
    const float x_fly = x_top + 1.6f * len.canopy;
    const glm::vec3 fly_start = on_path(t, x_fly, canopy);
    add(fly_start, along_path(t, x_fly, 0.3f), Segment::flyout);

    // Flyout: back and up (still facing ahead), to the start of the overview orbit behind the walk.
    const glm::vec3 centre = world_centre(t);
    const glm::vec2 d = t.path_direction(x_fly);
    const float heading = std::atan2(d.y, d.x);
    const glm::vec3 ahead(d.x, 0.0f, d.y);
    add(fly_start - 0.06f * size * ahead + glm::vec3(0.0f, 0.12f * size, 0.0f), ahead + glm::vec3(0.0f, -0.45f, 0.0f),
        Segment::flyout);
    // Overview: a quarter orbit around the centre, looking at it.
    const float radius = shape.overview_radius * size, height = shape.overview_height * size;
    const float arc = shape.overview_arc_deg * kPi / 180.0f;
    for (int k = 0; k <= 3; ++k) {
        const glm::vec3 position = centre + radius * horizontal(heading + kPi + arc * static_cast<float>(k) / 3.0f) +
                                   glm::vec3(0.0f, height, 0.0f);
        add(position, centre - position, k < 3 ? Segment::overview : Segment::return_to_ground);
    }
    // Return: down in an arc to the path behind the walk's start, landing where the walk began.
    const glm::vec3 landing = keys.front().eye;
    const glm::vec3 middle =
        centre + 0.35f * size * horizontal(heading + kPi + 0.5f * arc) + glm::vec3(0.0f, 0.16f * size, 0.0f);
    add(middle, 0.5f * (landing + centre) - middle, Segment::return_to_ground);
    const float x_approach = x0 - 0.08f * size;
    add(on_path(t, x_approach, std::max(0.05f * size, 12.0f)), along_path(t, x_approach, 0.35f),
        Segment::return_to_ground);
    const float x_final = x0 - 0.03f * size;
    add(on_path(t, x_final, eye + 1.0f), along_path(t, x_final, 0.1f), Segment::return_to_ground);
    add(landing, keys.front().look, Segment::return_to_ground);
    return keys;
}

std::vector<PathPose> sample_world_path(const WorldGround& ground, int frames,
                                        const std::optional<WorldPathShape>& given,
                                        const std::array<float, kSegmentCount>& shares) {
    const WorldPathShape shape = given ? *given : path_shape_for(ground);
    const CameraPath path(make_world_path_keys(ground, shape));
    std::vector<PathPose> poses = path.sample(frames, shares);
    for (PathPose& pose : poses) {
        const float height = ground.height(pose.eye.x, pose.eye.z);
        // Walking follows the ground between keys; elsewhere the spline is only kept off it.
        pose.eye.y = pose.segment == Segment::ground ? height + shape.eye_height_m
                                                     : std::max(pose.eye.y, height + shape.min_clearance_m);
    }
    return poses;
}

}  // namespace sample_game
