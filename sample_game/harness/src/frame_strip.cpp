#include "sample_game/harness/frame_strip.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "formatted.h"
#include "sample_game/harness/frame_sheet.h"

namespace sample_game {
namespace {

// A window of kStripFrames frames starting at `first`, moved back so that it ends on the path.
std::size_t clamp_start(std::size_t first, std::size_t frames) {
    return frames >= kStripFrames ? std::min(first, frames - kStripFrames) : 0;
}

std::string frame_label(const StripRecorder::Frame& f, bool largest) {
    std::string label = formatted("LOD f%d %s", f.frame, std::string(to_string(f.segment)).c_str());
    if (f.temporal_error >= 0.0) label += formatted(" temporal %.2f", f.temporal_error);
    return largest ? label + " (largest)" : label;
}

// |(M_f − M_{f−1}) − (R_f − R_{f−1})| per channel, × kStripErrorGain and clamped: what temporal_error
// averages, as a picture.
engine::Image temporal_error_picture(const engine::Image& previous, const engine::Image& current,
                                     const splat_lod::eval::FloatImage& reference_previous,
                                     const splat_lod::eval::FloatImage& reference_current) {
    const int w = current.width, h = current.height;
    for (const auto* image : {&reference_previous, &reference_current})
        if (previous.width != w || previous.height != h || image->width != w || image->height != h)
            engine::fail(formatted("sample_game_harness: frame strip: a frame of %dx%d against a reference of %dx%d", w,
                                   h, image->width, image->height));
    engine::Image out{w, h, std::vector<std::uint8_t>(current.rgba.size(), 255)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const double change = double(current.pixel(x, y)[c]) - double(previous.pixel(x, y)[c]);
                const double reference_change =
                    255.0 * (double(reference_current.at(x, y, c)) - double(reference_previous.at(x, y, c)));
                const double error = std::abs(change - reference_change) * kStripErrorGain;
                out.pixel(x, y)[c] = static_cast<std::uint8_t>(std::min(255.0, std::round(error)));
            }
    return out;
}

}  // namespace

double temporal_error(const splat_lod::eval::FloatImage& previous, const splat_lod::eval::FloatImage& current,
                      const splat_lod::eval::FloatImage& reference_previous,
                      const splat_lod::eval::FloatImage& reference_current) {
    for (const auto* image : {&current, &reference_previous, &reference_current})
        if (image->width != previous.width || image->height != previous.height ||
            image->rgb.size() != previous.rgb.size())
            engine::fail(formatted("sample_game_harness: temporal_error: an image of %dx%d against one of %dx%d",
                                   image->width, image->height, previous.width, previous.height));
    if (previous.rgb.empty()) return 0.0;
    double sum = 0.0;
    for (std::size_t i = 0; i < previous.rgb.size(); ++i) {
        const double change = static_cast<double>(current.rgb[i]) - static_cast<double>(previous.rgb[i]);
        const double reference_change =
            static_cast<double>(reference_current.rgb[i]) - static_cast<double>(reference_previous.rgb[i]);
        sum += std::abs(change - reference_change);
    }
    return 255.0 * sum / static_cast<double>(previous.rgb.size());
}

std::size_t strip_start(std::size_t frame, std::size_t frames) {
    return clamp_start(frame >= kStripFramesBefore ? frame - kStripFramesBefore : 0, frames);
}

StripRecorder::StripRecorder(std::size_t frames, std::size_t fallback_start)
    : frames_(frames), window_start_(clamp_start(fallback_start, frames)) {}

void StripRecorder::add(int frame, Segment segment, const engine::Image& image, double temporal_error) {
    recent_.push_back({frame, segment, image, temporal_error});
    if (recent_.size() > kStripFrames) recent_.pop_front();
    const auto f = static_cast<std::size_t>(std::max(frame, 0));
    if (temporal_error > best_error_) {
        // A new worst pair: its window's frames so far are among the recent ones (the window starts
        // at most kStripFrames − 1 frames before this one), the rest follow.
        best_error_ = temporal_error;
        window_start_ = strip_start(f, frames_);
        window_.clear();
        for (const Frame& kept : recent_)
            if (static_cast<std::size_t>(kept.frame) >= window_start_) window_.push_back(kept);
        return;
    }
    if (f >= window_start_ && f < window_start_ + kStripFrames) window_.push_back(recent_.back());
}

bool StripRecorder::write(const std::filesystem::path& path,
                          const std::map<int, splat_lod::eval::FloatImage>& reference, int thumbnail_width) const {
    if (window_.empty()) return false;
    FrameSheet sheet(thumbnail_width, static_cast<int>(window_.size()));
    const bool any_reference =
        std::any_of(window_.begin(), window_.end(), [&](const Frame& f) { return reference.count(f.frame) > 0; });
    if (any_reference)
        for (const Frame& f : window_) {
            const auto it = reference.find(f.frame);
            if (it == reference.end())
                sheet.add_blank(formatted("f%d: no reference", f.frame));
            else
                sheet.add(splat_lod::eval::to_rgba8(it->second), formatted("reference f%d", f.frame));
        }
    for (const Frame& f : window_) sheet.add(f.image, frame_label(f, measured() && f.temporal_error == best_error_));
    // Where a frame and the one before both have a reference: the temporal error's picture.
    const auto pair_reference = [&](std::size_t k) {
        const auto now = reference.find(window_[k].frame), before = reference.find(window_[k].frame - 1);
        return k > 0 && now != reference.end() && before != reference.end() &&
                       window_[k - 1].frame + 1 == window_[k].frame
                   ? std::make_pair(&before->second, &now->second)
                   : std::make_pair(nullptr, nullptr);
    };
    bool any_pair = false;
    for (std::size_t k = 0; k < window_.size(); ++k) any_pair = any_pair || pair_reference(k).first != nullptr;
    for (std::size_t k = 0; any_pair && k < window_.size(); ++k) {
        const auto [before, now] = pair_reference(k);
        if (!before)
            sheet.add_blank(formatted("f%d: no reference pair", window_[k].frame));
        else
            sheet.add(temporal_error_picture(window_[k - 1].image, window_[k].image, *before, *now),
                      formatted("|dLOD - dref| f%d-%d x%d", window_[k].frame, window_[k - 1].frame, kStripErrorGain));
    }
    sheet.write(path);
    return true;
}

}  // namespace sample_game
