#include "sample_game/camera_path.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "engine/core/error.h"

namespace sample_game {
namespace {

// Arc length is tabulated at this many parameter steps per span; a step is then a nearly straight
// piece, so the inverse is accurate to well under a percent of a frame's step.
constexpr int kArcSteps = 256;

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

[[noreturn]] void key_error(std::size_t index, const std::string& problem) {
    engine::fail("sample_game::CameraPath: key " + std::to_string(index) + ": " + problem);
}

// Barry–Goldman pyramid of the Catmull-Rom span between p[1] and p[2] at knot value t ∈ [k1, k2].
glm::vec3 barry_goldman(const std::array<glm::vec3, 4>& p, const std::array<float, 4>& k, float t) {
    auto lerp = [](const glm::vec3& a, const glm::vec3& b, float ka, float kb, float x) {
        return (kb - x) / (kb - ka) * a + (x - ka) / (kb - ka) * b;
    };
    const glm::vec3 a1 = lerp(p[0], p[1], k[0], k[1], t);
    const glm::vec3 a2 = lerp(p[1], p[2], k[1], k[2], t);
    const glm::vec3 a3 = lerp(p[2], p[3], k[2], k[3], t);
    const glm::vec3 b1 = lerp(a1, a2, k[0], k[2], t);
    const glm::vec3 b2 = lerp(a2, a3, k[1], k[3], t);
    return lerp(b1, b2, k[1], k[2], t);
}

}  // namespace

std::string_view to_string(Segment segment) {
    return kSegmentNames[static_cast<std::size_t>(segment)];
}

glm::vec3 pose_velocity(const std::vector<PathPose>& poses, std::size_t i) {
    return i == 0 || i >= poses.size() ? glm::vec3(0.0f) : poses[i].eye - poses[i - 1].eye;
}

CameraPath::CameraPath(std::vector<PathKey> keys) : keys_(std::move(keys)) {
    if (keys_.size() < 2)
        engine::fail("sample_game::CameraPath: needs at least two keys, got " + std::to_string(keys_.size()));
    for (std::size_t i = 0; i < keys_.size(); ++i) {
        PathKey& key = keys_[i];
        if (!finite(key.eye)) key_error(i, "the eye position is not finite");
        if (!finite(key.look) || !(glm::length(key.look) > 1e-6f))
            key_error(i, "the look direction is zero or not finite");
        key.look = glm::normalize(key.look);
        if (i > 0 && !(glm::distance(key.eye, keys_[i - 1].eye) > 1e-3f))
            key_error(i, "the eye repeats the previous key's");
        if (i > 0 && key.segment < keys_[i - 1].segment)
            key_error(i, "segments must not go back (" + std::string(to_string(key.segment)) + " after " +
                             std::string(to_string(keys_[i - 1].segment)) + ")");
    }
    // Phantom keys mirror the second and the second-to-last key, so the end spans start and end
    // heading at their neighbours.
    const std::size_t n = keys_.size();
    eyes_.push_back(2.0f * keys_[0].eye - keys_[1].eye);
    looks_.push_back(2.0f * keys_[0].look - keys_[1].look);
    for (const auto& key : keys_) {
        eyes_.push_back(key.eye);
        looks_.push_back(key.look);
    }
    eyes_.push_back(2.0f * keys_[n - 1].eye - keys_[n - 2].eye);
    looks_.push_back(2.0f * keys_[n - 1].look - keys_[n - 2].look);

    spans_.resize(n - 1);
    for (std::size_t s = 0; s < spans_.size(); ++s) {
        Span& span = spans_[s];
        for (int j = 1; j < 4; ++j)  // centripetal: knot intervals are the square roots of the chord lengths
            span.knots[static_cast<std::size_t>(j)] =
                span.knots[static_cast<std::size_t>(j - 1)] +
                std::sqrt(
                    glm::distance(eyes_[s + static_cast<std::size_t>(j)], eyes_[s + static_cast<std::size_t>(j) - 1]));
        span.arc.resize(kArcSteps + 1, 0.0f);
        glm::vec3 previous = eval_span(s, 0.0f, false);
        for (int k = 1; k <= kArcSteps; ++k) {
            const glm::vec3 p = eval_span(s, static_cast<float>(k) / kArcSteps, false);
            span.arc[static_cast<std::size_t>(k)] =
                span.arc[static_cast<std::size_t>(k) - 1] + glm::distance(p, previous);
            previous = p;
        }
    }
}

glm::vec3 CameraPath::eval_span(std::size_t span, float u, bool direction) const {
    const auto& source = direction ? looks_ : eyes_;
    const std::array<glm::vec3, 4> p{source[span], source[span + 1], source[span + 2], source[span + 3]};
    const auto& k = spans_[span].knots;
    return barry_goldman(p, k, k[1] + std::clamp(u, 0.0f, 1.0f) * (k[2] - k[1]));
}

PathPose CameraPath::at(float u) const {
    u = std::clamp(u, 0.0f, static_cast<float>(spans()));
    const std::size_t span = std::min(static_cast<std::size_t>(u), spans() - 1);
    const float local = u - static_cast<float>(span);
    PathPose pose;
    pose.eye = eval_span(span, local, false);
    const glm::vec3 look = eval_span(span, local, true);
    // Keys never look in opposite directions at neighbours, so the blend does not vanish; guard anyway.
    pose.forward = glm::length(look) > 1e-6f ? glm::normalize(look) : keys_[span].look;
    pose.segment = keys_[span].segment;
    pose.t = u / static_cast<float>(spans());
    return pose;
}

float CameraPath::length() const {
    float total = 0.0f;
    for (const auto& span : spans_) total += span.arc.back();
    return total;
}

std::array<float, kSegmentCount> CameraPath::segment_lengths() const {
    std::array<float, kSegmentCount> lengths{};
    for (std::size_t s = 0; s < spans_.size(); ++s)
        lengths[static_cast<std::size_t>(keys_[s].segment)] += spans_[s].arc.back();
    return lengths;
}

float CameraPath::span_parameter(std::size_t span, float s) const {
    const auto& arc = spans_[span].arc;
    s = std::clamp(s, 0.0f, arc.back());
    const auto it = std::lower_bound(arc.begin(), arc.end(), s);
    const auto k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - arc.begin()));
    const float step = arc[k] - arc[k - 1];
    const float fraction = step > 0.0f ? (s - arc[k - 1]) / step : 0.0f;
    return static_cast<float>(span) + (static_cast<float>(k - 1) + fraction) / kArcSteps;
}

std::vector<PathPose> CameraPath::sample(int frames, const std::array<float, kSegmentCount>& shares) const {
    // The segments the path visits, in order, with their spans.
    struct Part {
        Segment segment;
        std::size_t first_span, end_span;
        float length = 0.0f;
        int frames = 0;
    };
    std::vector<Part> parts;
    for (std::size_t s = 0; s < spans_.size(); ++s) {
        if (parts.empty() || parts.back().segment != keys_[s].segment)
            parts.push_back({keys_[s].segment, s, s, 0.0f, 0});
        parts.back().end_span = s + 1;
        parts.back().length += spans_[s].arc.back();
    }
    if (frames < static_cast<int>(parts.size()) || frames < 2)
        engine::fail("sample_game::CameraPath::sample(): " + std::to_string(frames) + " frames cannot cover " +
                     std::to_string(parts.size()) + " segments (at least one frame each, two in all)");
    float share_sum = 0.0f;
    for (const auto& part : parts) share_sum += std::max(shares[static_cast<std::size_t>(part.segment)], 0.0f);
    int assigned = 0;
    for (auto& part : parts) {
        const float share = share_sum > 0.0f
                                ? std::max(shares[static_cast<std::size_t>(part.segment)], 0.0f) / share_sum
                                : 1.0f / static_cast<float>(parts.size());
        part.frames = std::max(1, static_cast<int>(std::lround(share * static_cast<float>(frames))));
        assigned += part.frames;
    }
    // Rounding left a few frames over or short: take them from (or give them to) the largest parts.
    while (assigned != frames) {
        auto largest = std::max_element(parts.begin(), parts.end(),
                                        [](const Part& a, const Part& b) { return a.frames < b.frames; });
        largest->frames += assigned < frames ? 1 : -1;
        assigned += assigned < frames ? 1 : -1;
    }

    std::vector<PathPose> poses;
    poses.reserve(static_cast<std::size_t>(frames));
    for (std::size_t p = 0; p < parts.size(); ++p) {
        const Part& part = parts[p];
        const bool last = p + 1 == parts.size();
        // Frames start at the segment's beginning; the last segment also ends exactly on the last key.
        const float step = last && part.frames > 1 ? part.length / static_cast<float>(part.frames - 1)
                                                   : part.length / static_cast<float>(part.frames);
        for (int j = 0; j < part.frames; ++j) {
            float s = last && part.frames == 1 ? part.length : step * static_cast<float>(j);
            std::size_t span = part.first_span;
            while (span + 1 < part.end_span && s > spans_[span].arc.back()) s -= spans_[span++].arc.back();
            PathPose pose = at(span_parameter(span, s));
            pose.segment = part.segment;
            poses.push_back(pose);
        }
    }
    for (std::size_t i = 0; i < poses.size(); ++i)
        poses[i].t = poses.size() > 1 ? static_cast<float>(i) / static_cast<float>(poses.size() - 1) : 0.0f;
    return poses;
}

}  // namespace sample_game
