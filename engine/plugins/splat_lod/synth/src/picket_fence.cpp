// The picket fence: a strictly periodic pattern of opaque boards and empty gaps, the classic
// aliasing test (a fence seen small turns into moiré unless it is filtered).
#include "splat_lod/synth/synth_common.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace splat_lod::synth {
namespace {

// Board tiles at detail 1: 5 columns across a board, a row every 2 cm.
constexpr int kBoardColumns = 5;
constexpr float kBoardRowSpacing = 0.02f;
constexpr float kBoardClearance = 0.04f;  // boards stop above the ground, as real ones do
constexpr float kRailHeight = 0.07f;
constexpr float kRailSetBack = 0.025f;  // rails sit behind the boards
constexpr float kTipHeight = 0.06f;     // the pointed top
// Room for the clearance, two rails below the tips and the tips themselves.
constexpr float kMinFenceHeight = 0.4f;

struct FenceFrame {
    glm::vec3 start{0.0f};
    glm::vec3 direction{1.0f, 0.0f, 0.0f};  // horizontal, unit
    glm::vec3 normal{0.0f, 0.0f, -1.0f};    // up × direction: the rails' side
    float length = 0.0f;                    // horizontal
    float rise = 0.0f;                      // end.y − start.y

    glm::vec3 ground_at(float along) const {
        return start + direction * along + glm::vec3(0.0f, rise * along / length, 0.0f);
    }
};

glm::vec3 paint_colour(float height_above_ground, float board_tint, Rng& rng) {
    const glm::vec3 cream(0.93f, 0.91f, 0.84f), dirt(0.55f, 0.50f, 0.42f);
    // Splashed dirt near the ground, fading out over 15 cm.
    const float dirt_amount = 0.5f * (1.0f - glm::smoothstep(0.0f, 0.15f, height_above_ground));
    return mix_rgb(cream, dirt, dirt_amount) * board_tint * rng.uniform(0.97f, 1.01f);
}

void append_board(SplatCloud& cloud, const FenceFrame& frame, float along, float height, float detail, Rng& rng) {
    const int columns = std::max(2, static_cast<int>(std::lround(kBoardColumns * std::sqrt(detail))));
    const float tile_width = kPicketBoardWidth / static_cast<float>(columns);
    const float row_spacing = kBoardRowSpacing / std::sqrt(detail);
    const float board_height = height - kBoardClearance;
    const int rows = std::max(2, static_cast<int>(std::ceil(board_height / row_spacing)));
    const float tile_height = board_height / static_cast<float>(rows);
    const float board_tint = rng.uniform(0.95f, 1.02f);
    const glm::vec3 foot = frame.ground_at(along);
    for (int row = 0; row < rows; ++row) {
        const float y = kBoardClearance + (static_cast<float>(row) + 0.5f) * tile_height;
        // The pointed top: the half-width shrinks linearly to zero at the board's top.
        const float half_width = 0.5f * kPicketBoardWidth * std::min(1.0f, (height - y) / kTipHeight);
        for (int column = 0; column < columns; ++column) {
            const float x = (static_cast<float>(column) + 0.5f) * tile_width - 0.5f * kPicketBoardWidth;
            if (std::abs(x) > half_width) continue;
            GaussianDraft g;
            g.position = foot + frame.direction * x + glm::vec3(0.0f, y, 0.0f);
            g.axis_x = frame.direction;
            g.axis_y = glm::vec3(0.0f, 1.0f, 0.0f);
            // 0.6 × the tile width merges the columns into an even surface yet keeps the board's
            // edge sharp (about one tile of fall-off); rows overlap more (0.8 ×), which hides the
            // tiling, like wood grain running along the board.
            g.scale = glm::vec3(0.6f * tile_width, 0.8f * tile_height, 0.004f);
            g.rgb = paint_colour(y, board_tint, rng);
            g.opacity_logit = rng.uniform(4.0f, 5.0f);
            append_gaussian(cloud, g);
        }
    }
}

void append_rail(SplatCloud& cloud, const FenceFrame& frame, float rail_centre_height, float detail, Rng& rng) {
    const float tile = 0.025f / std::sqrt(detail);
    const int segments = std::max(2, static_cast<int>(std::ceil(frame.length / tile)));
    const int rows = std::max(2, static_cast<int>(std::lround(3.0f * std::sqrt(detail))));
    const float segment_length = frame.length / static_cast<float>(segments);
    const float row_height = kRailHeight / static_cast<float>(rows);
    const glm::vec3 rise_direction = glm::normalize(frame.direction * frame.length + glm::vec3(0.0f, frame.rise, 0.0f));
    for (int s = 0; s < segments; ++s) {
        const float along = (static_cast<float>(s) + 0.5f) * segment_length;
        for (int r = 0; r < rows; ++r) {
            const float y = rail_centre_height + ((static_cast<float>(r) + 0.5f) * row_height - 0.5f * kRailHeight);
            GaussianDraft g;
            g.position = frame.ground_at(along) + frame.normal * kRailSetBack + glm::vec3(0.0f, y, 0.0f);
            g.axis_x = rise_direction;
            g.axis_y = glm::vec3(0.0f, 1.0f, 0.0f);
            g.scale = glm::vec3(0.6f * segment_length, 0.6f * row_height, 0.008f);
            // Rails are in the boards' shadow for most of the day.
            g.rgb = glm::vec3(0.80f, 0.78f, 0.71f) * rng.uniform(0.92f, 1.02f);
            g.opacity_logit = rng.uniform(4.0f, 5.0f);
            append_gaussian(cloud, g);
        }
    }
}

}  // namespace

FenceSplats append_picket_fence(SplatCloud& cloud, const glm::vec3& start, const glm::vec3& end, float height, Rng& rng,
                                float detail) {
    require_finite(start, "append_picket_fence", "start");
    require_finite(end, "append_picket_fence", "end");
    require_positive(height, "append_picket_fence", "height");
    require_detail(detail, "append_picket_fence");
    if (height < kMinFenceHeight)
        engine::fail("splat_lod::synth::append_picket_fence(): height " + number_text(height) +
                     " m is too low for a picket fence (at least " + number_text(kMinFenceHeight) + " m)");
    FenceFrame frame;
    frame.start = start;
    const glm::vec3 horizontal(end.x - start.x, 0.0f, end.z - start.z);
    frame.length = std::sqrt(glm::dot(horizontal, horizontal));
    if (!(frame.length >= kPicketPitch))
        engine::fail("splat_lod::synth::append_picket_fence(): start and end are " + number_text(frame.length) +
                     " m apart horizontally, less than one board pitch (" + number_text(kPicketPitch) + " m)");
    require_count(frame.length / kPicketPitch * (height / kBoardRowSpacing) * kBoardColumns * detail,
                  "append_picket_fence");
    frame.direction = horizontal / frame.length;
    frame.normal = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), frame.direction);
    frame.rise = end.y - start.y;

    FenceSplats result;
    result.board_count = static_cast<int>(std::floor((frame.length - kPicketBoardWidth) / kPicketPitch)) + 1;
    // Centre the row of boards so that both ends of the fence look alike.
    const float span = static_cast<float>(result.board_count - 1) * kPicketPitch + kPicketBoardWidth;
    const float first_centre = 0.5f * (frame.length - span) + 0.5f * kPicketBoardWidth;
    result.boards.begin = cloud.size();
    for (int b = 0; b < result.board_count; ++b)
        append_board(cloud, frame, first_centre + static_cast<float>(b) * kPicketPitch, height, detail, rng);
    result.boards.end = result.rails.begin = cloud.size();
    append_rail(cloud, frame, 0.25f * height, detail, rng);
    append_rail(cloud, frame, height - kTipHeight - 0.12f, detail, rng);
    result.rails.end = cloud.size();
    return result;
}

}  // namespace splat_lod::synth
