#pragma once
// The walkthrough's camera path: a smooth curve through key poses, stepped per frame (not per
// second) so that a profile run is the same camera sequence every time.
//
// Curve: centripetal Catmull-Rom (α = 0.5, Barry–Goldman evaluation) through the key positions;
// unlike the uniform variant it never forms cusps or loops between unevenly spaced keys, which the
// walk (metres apart) and the overview (hundreds of metres apart) are. The end spans use mirrored
// phantom keys. The view direction is the same spline over the keys' unit look directions (same
// knots), normalised, so it turns smoothly too.
//
// Segments: each span between two keys belongs to the segment named by its first key (ground,
// canopy, flyout, overview, return). sample() gives every segment a fixed share of the frames and
// places that segment's frames at even arc-length steps along it (speed constant within a segment,
// a walk slower than a flight), which makes per-segment statistics comparable between runs of
// different lengths.
#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace sample_game {

enum class Segment { ground, canopy, flyout, overview, return_to_ground };
inline constexpr std::array<std::string_view, 5> kSegmentNames{"ground", "canopy", "flyout", "overview", "return"};
inline constexpr std::size_t kSegmentCount = kSegmentNames.size();
std::string_view to_string(Segment segment);

struct PathKey {
    glm::vec3 eye{0.0f};
    glm::vec3 look{0.0f, 0.0f, -1.0f};  // view direction (any length > 0; normalised)
    Segment segment = Segment::ground;  // of the span from this key to the next
};

struct PathPose {
    glm::vec3 eye{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit view direction
    Segment segment = Segment::ground;
    float t = 0.0f;  // position along the whole path by frame, 0 (first frame) .. 1 (last frame)
};

// How far the camera moves from pose i − 1 to pose i of a walk (zero at the first pose): what the
// streamer's cut anticipates with (GameWorld::update_streaming).
glm::vec3 pose_velocity(const std::vector<PathPose>& poses, std::size_t i);

class CameraPath {
public:
    // At least two keys, consecutive eyes distinct, look directions non-zero and finite, and the
    // segments in non-decreasing order; throws engine::Error naming the first bad key otherwise.
    explicit CameraPath(std::vector<PathKey> keys);

    // The pose at curve parameter u ∈ [0, spans()] (span i is [i, i + 1]); not arc-length uniform.
    PathPose at(float u) const;
    std::size_t spans() const { return keys_.size() - 1; }
    const std::vector<PathKey>& keys() const { return keys_; }
    // Arc length of the whole curve and of each segment (0 for a segment the path does not visit).
    float length() const;
    std::array<float, kSegmentCount> segment_lengths() const;

    // `frames` poses (at least as many as the path has segments): segment k gets round(share_k ·
    // frames) of them (at least one; shares normalised over the segments present), spread at even
    // arc-length steps; the first pose is the first key and the last the last key.
    std::vector<PathPose> sample(int frames, const std::array<float, kSegmentCount>& shares) const;

private:
    struct Span {
        // Centripetal knots of the four control points around this span, and the cumulative arc
        // length at kArcSteps + 1 evenly spaced parameters (for inverting arc length).
        std::array<float, 4> knots{};
        std::vector<float> arc;
    };
    glm::vec3 eval_span(std::size_t span, float u, bool direction) const;
    // Parameter u ∈ [span, span + 1] at arc length s from the start of that span.
    float span_parameter(std::size_t span, float s) const;

    std::vector<PathKey> keys_;
    std::vector<glm::vec3> eyes_, looks_;  // with one phantom key at each end
    std::vector<Span> spans_;
};

// The default frame shares of the segments: the walk and the overview (the comparison) get the
// most frames.
inline constexpr std::array<float, kSegmentCount> kDefaultSegmentShares{0.22f, 0.16f, 0.16f, 0.26f, 0.20f};

}  // namespace sample_game
