// The forward-facing room: its fixed layout, the capture's camera grid and the held-out views.
#include "splat_lod/synth/synth_common.h"

#include <array>
#include <cmath>
#include <cstdio>

#include "engine/core/error.h"
#include "room_parts.h"
#include "splat_lod/synth/room_scene.h"

namespace splat_lod::synth {
namespace {

using room::Panel;

constexpr float kW = kRoomHalfWidth;
constexpr float kLength = kRoomOpenZ - kRoomFarZ;

// Floor, rug, walls and ceiling.
void add_shell(SplatCloud& cloud, std::uint64_t seed, float detail, std::uint64_t& stream) {
    Rng floor_rng(seed, stream++);
    room::tile_panel(cloud, {{-kW, 0.0f, kRoomOpenZ}, {2.0f * kW, 0.0f, 0.0f}, {0.0f, 0.0f, -kLength}}, 0.05f, detail,
                     room::floor_planks(seed), floor_rng);
    Rng rug_rng(seed, stream++);
    const float rug_x0 = -1.4f, rug_x1 = 1.4f, rug_z0 = -4.4f, rug_z1 = -1.6f;
    room::tile_panel(cloud, {{rug_x0, 0.01f, rug_z1}, {rug_x1 - rug_x0, 0.0f, 0.0f}, {0.0f, 0.0f, rug_z0 - rug_z1}},
                     0.025f, detail, room::rug_pattern(rug_x0, rug_z0, rug_x1, rug_z1), rug_rng);
    Rng far_rng(seed, stream++);
    room::tile_panel(cloud, {{-kW, 0.0f, kRoomFarZ}, {2.0f * kW, 0.0f, 0.0f}, {0.0f, kRoomHeight, 0.0f}}, 0.035f,
                     detail, room::striped_wallpaper(), far_rng);
    Rng left_rng(seed, stream++);
    room::tile_panel(cloud, {{-kW, 0.0f, kRoomFarZ}, {0.0f, kRoomHeight, 0.0f}, {0.0f, 0.0f, kLength}}, 0.05f, detail,
                     room::panelled_wall(seed), left_rng);
    Rng right_rng(seed, stream++);
    room::tile_panel(cloud, {{kW, 0.0f, kRoomFarZ}, {0.0f, 0.0f, kLength}, {0.0f, kRoomHeight, 0.0f}}, 0.05f, detail,
                     room::panelled_wall(seed + 1), right_rng);
    Rng ceiling_rng(seed, stream++);
    room::tile_panel(cloud, {{-kW, kRoomHeight, kRoomFarZ}, {2.0f * kW, 0.0f, 0.0f}, {0.0f, 0.0f, kLength}}, 0.1f,
                     detail, room::plain({0.90f, 0.89f, 0.86f}, 0.04f, 0.85f), ceiling_rng);
}

// One shelf of book spines from x0 to x1 standing on y, their fronts at z.
void add_books(SplatCloud& cloud, float x0, float x1, float y, float z, float detail, Rng& rng) {
    const std::array<glm::vec3, 6> palette = {{{0.60f, 0.10f, 0.10f},
                                               {0.10f, 0.22f, 0.50f},
                                               {0.12f, 0.40f, 0.20f},
                                               {0.85f, 0.70f, 0.25f},
                                               {0.30f, 0.15f, 0.35f},
                                               {0.88f, 0.86f, 0.80f}}};
    float x = x0;
    while (x < x1 - 0.02f) {
        const float width = std::min(rng.uniform(0.02f, 0.05f), x1 - x);
        const float height = rng.uniform(0.22f, 0.36f);
        const int colour = rng.uniform_int(0, static_cast<int>(palette.size()) - 1);
        const float tint = rng.uniform(0.8f, 1.1f);
        if (rng.chance(0.06f)) {  // a gap where a book is out
            x += width;
            continue;
        }
        const glm::vec3 base = palette[static_cast<std::size_t>(colour)] * tint;
        const float band = y + 0.75f * height;  // a pale title band near the top of the spine
        const room::Paint spine = [base, band](const glm::vec3& p, const glm::vec3& n, Rng& r) {
            const glm::vec3 rgb = std::abs(p.y - band) < 0.012f ? glm::vec3(0.92f, 0.88f, 0.70f) : base;
            return rgb * sun_shade(n, 0.7f) * r.uniform(0.94f, 1.06f);
        };
        room::tile_panel(cloud, {{x, y, z}, {width, 0.0f, 0.0f}, {0.0f, height, 0.0f}}, 0.015f, detail, spine, rng);
        x += width;
    }
}

// A bookshelf against the far wall, left of centre: two sides, six boards, five shelves of books.
void add_bookshelf(SplatCloud& cloud, std::uint64_t seed, float detail, std::uint64_t& stream) {
    Rng rng(seed, stream++);
    const float x0 = -2.6f, x1 = -0.6f, back = kRoomFarZ, front = kRoomFarZ + 0.35f, top = 2.2f;
    const room::Paint wood = room::plain({0.32f, 0.20f, 0.12f}, 0.06f, 0.6f);
    room::tile_box(cloud, {x0, 0.0f, back}, {x0 + 0.04f, top, front}, 0.025f, detail, wood, rng);
    room::tile_box(cloud, {x1 - 0.04f, 0.0f, back}, {x1, top, front}, 0.025f, detail, wood, rng);
    constexpr int kShelves = 5;
    const float pitch = (top - 0.03f) / kShelves;
    for (int s = 0; s <= kShelves; ++s) {
        const float y = pitch * static_cast<float>(s);
        room::tile_box(cloud, {x0 + 0.04f, y, back}, {x1 - 0.04f, y + 0.03f, front}, 0.025f, detail, wood, rng);
        if (s < kShelves) add_books(cloud, x0 + 0.05f, x1 - 0.05f, y + 0.03f, front - 0.05f, detail, rng);
    }
}

// A table with a tiled top, a striped sofa, a cabinet of drawers, two crates near the capture.
void add_furniture(SplatCloud& cloud, std::uint64_t seed, float detail, std::uint64_t& stream) {
    Rng table_rng(seed, stream++);
    room::tile_box(cloud, {-0.8f, 0.70f, -3.4f}, {0.8f, 0.75f, -2.5f}, 0.02f, detail,
                   room::checker({0.92f, 0.90f, 0.84f}, {0.20f, 0.32f, 0.45f}, 0.06f), table_rng);
    const room::Paint leg = room::plain({0.25f, 0.16f, 0.10f}, 0.05f, 0.6f);
    for (const float x : {-0.76f, 0.71f})
        for (const float z : {-3.36f, -2.59f})
            room::tile_box(cloud, {x, 0.0f, z}, {x + 0.05f, 0.70f, z + 0.05f}, 0.02f, detail, leg, table_rng);
    Rng sofa_rng(seed, stream++);
    const room::Paint fabric = room::fabric_stripes({0.70f, 0.62f, 0.48f}, {0.35f, 0.12f, 0.14f}, 0.05f);
    room::tile_box(cloud, {1.0f, 0.0f, -5.6f}, {2.8f, 0.45f, -4.7f}, 0.025f, detail, fabric, sofa_rng);
    room::tile_box(cloud, {1.0f, 0.45f, -5.6f}, {2.8f, 0.95f, -5.35f}, 0.025f, detail, fabric, sofa_rng);
    for (const float x : {1.0f, 2.62f})
        room::tile_box(cloud, {x, 0.45f, -5.35f}, {x + 0.18f, 0.65f, -4.7f}, 0.025f, detail, fabric, sofa_rng);
    Rng cabinet_rng(seed, stream++);
    room::tile_box(cloud, {-kW, 0.0f, -5.0f}, {-kW + 0.5f, 1.1f, -3.4f}, 0.02f, detail, room::drawers(0.0f, 0.275f),
                   cabinet_rng);
    Rng crate_rng(seed, stream++);
    room::tile_box(cloud, {-1.2f, 0.0f, -2.2f}, {-0.6f, 0.6f, -1.6f}, 0.02f, detail,
                   room::checker({0.75f, 0.16f, 0.12f}, {0.92f, 0.88f, 0.78f}, 0.075f), crate_rng);
    room::tile_box(cloud, {0.7f, 0.0f, -2.6f}, {1.15f, 0.4f, -2.15f}, 0.015f, detail,
                   room::checker({0.12f, 0.25f, 0.62f}, {0.95f, 0.95f, 0.92f}, 0.05f), crate_rng);
}

// A finely striped picture on the far wall and one of rings on the right wall.
void add_pictures(SplatCloud& cloud, std::uint64_t seed, float detail, std::uint64_t& stream) {
    Rng rng(seed, stream++);
    room::tile_panel(cloud, {{0.6f, 1.2f, kRoomFarZ + 0.02f}, {1.4f, 0.0f, 0.0f}, {0.0f, 0.9f, 0.0f}}, 0.012f, detail,
                     room::fine_stripes(0.03f), rng);
    const float x = kW - 0.02f;
    room::tile_panel(cloud, {{x, 1.3f, -4.2f}, {0.0f, 0.0f, 1.2f}, {0.0f, 0.8f, 0.0f}}, 0.015f, detail,
                     room::rings({x, 1.7f, -3.6f}, 0.025f), rng);
}

}  // namespace

SplatCloud make_room_scene(const RoomOptions& options) {
    require_detail(options.detail, "make_room_scene");
    SplatCloud cloud;
    // Every object draws from its own stream (as in the garden): one object's count never shifts
    // another's random numbers.
    std::uint64_t stream = 0;
    add_shell(cloud, options.seed, options.detail, stream);
    add_bookshelf(cloud, options.seed, options.detail, stream);
    add_furniture(cloud, options.seed, options.detail, stream);
    add_pictures(cloud, options.seed, options.detail, stream);
    return cloud;
}

namespace {

// A camera at `eye` turned `yaw_deg` to the left of −z and pitched `pitch_deg` up, 50° field of view,
// focused 5 m ahead.
eval::CameraPose room_pose(const std::string& name, const glm::vec3& eye, float yaw_deg, float pitch_deg) {
    const SinCos yaw = sin_cos(static_cast<double>(yaw_deg) * kPi / 180.0);
    const SinCos pitch = sin_cos(static_cast<double>(pitch_deg) * kPi / 180.0);
    eval::CameraPose pose;
    pose.name = name;
    pose.eye = eye;
    pose.forward = glm::vec3(-yaw.sin * pitch.cos, pitch.sin, -yaw.cos * pitch.cos);
    const glm::vec3 right(yaw.cos, 0.0f, -yaw.sin);
    pose.up = glm::cross(right, pose.forward);
    pose.fov_y = static_cast<float>(50.0 * kPi / 180.0);
    pose.focus_distance = 5.0f;
    return pose;
}

}  // namespace

std::vector<eval::CameraPose> room_capture_cameras(int columns, int rows) {
    if (columns < 1 || columns > 64 || rows < 1 || rows > 64)
        engine::fail("splat_lod::synth::room_capture_cameras(): columns and rows must be 1..64, got " +
                     std::to_string(columns) + " x " + std::to_string(rows));
    std::vector<eval::CameraPose> poses;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) {
            const float fx = columns == 1 ? 0.5f : static_cast<float>(c) / static_cast<float>(columns - 1);
            const float fy = rows == 1 ? 0.5f : static_cast<float>(r) / static_cast<float>(rows - 1);
            const glm::vec3 eye(-1.0f + 2.0f * fx, 1.3f + 0.4f * fy, r % 2 == 0 ? 0.8f : 0.4f);
            // The sweep turns with the hand: left eyes look left, low eyes look further down.
            poses.push_back(room_pose("capture " + std::to_string(r) + "," + std::to_string(c), eye, 8.0f - 16.0f * fx,
                                      -2.0f - 5.0f * (1.0f - fy)));
        }
    return poses;
}

std::vector<eval::CameraPose> room_held_out_cameras() {
    struct View {
        glm::vec3 eye;
        float yaw, pitch;
    };
    const std::array<View, 8> views = {{
        {{-0.5f, 1.4f, 0.6f}, 12.0f, -5.0f},    // between grid eyes
        {{0.5f, 1.6f, 0.6f}, -14.0f, -3.0f},    // between grid eyes
        {{-0.2f, 1.5f, -0.6f}, 5.0f, -8.0f},    // a step into the room
        {{0.3f, 1.45f, -1.2f}, -20.0f, -6.0f},  // two steps in, beside the crates
        {{0.0f, 1.5f, 1.4f}, 0.0f, -4.0f},      // a step back
        {{-0.8f, 1.65f, 1.1f}, 18.0f, -10.0f},  // back and to the left
        {{0.8f, 1.35f, 0.2f}, -25.0f, -2.0f},   // turned to the sofa
        {{-0.3f, 1.25f, 0.0f}, 24.0f, 2.0f},    // turned to the shelf and the cabinet
    }};
    std::vector<eval::CameraPose> poses;
    for (std::size_t i = 0; i < views.size(); ++i)
        poses.push_back(room_pose("held-out " + std::to_string(i), views[i].eye, views[i].yaw, views[i].pitch));
    return poses;
}

std::string camera_path_json(const std::vector<eval::CameraPose>& poses) {
    std::string out = "[\n";
    char line[512];
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const eval::CameraPose& p = poses[i];
        const glm::vec3 t = p.target();
        std::snprintf(line, sizeof line,
                      "  {\"name\": \"%s\", \"eye\": [%.7g, %.7g, %.7g], \"target\": [%.7g, %.7g, %.7g], "
                      "\"up\": [%.7g, %.7g, %.7g], \"fov_y_deg\": %.7g}%s\n",
                      p.name.c_str(), static_cast<double>(p.eye.x), static_cast<double>(p.eye.y),
                      static_cast<double>(p.eye.z), static_cast<double>(t.x), static_cast<double>(t.y),
                      static_cast<double>(t.z), static_cast<double>(p.up.x), static_cast<double>(p.up.y),
                      static_cast<double>(p.up.z), static_cast<double>(p.fov_y) * 180.0 / kPi,
                      i + 1 < poses.size() ? "," : "");
        out += line;
    }
    return out + "]\n";
}

}  // namespace splat_lod::synth
