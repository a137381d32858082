#pragma once
// Whether levels pop: the temporal error of a frame against the reference, and the profile's frame
// strip of consecutive frames around the worst pair (frames_strip.png). GL-free.
//
// temporal_error of frame f, for a run whose images of f − 1 and f both have a reference: the mean
// over pixels and RGB channels of |(M_f − M_{f−1}) − (R_f − R_{f−1})| in 8-bit units (0..255), M the
// run's images and R the reference's. The camera's own motion changes both alike and cancels; what is
// left is change the reference does not have: a level or a chunk that switches in one frame (a pop),
// flicker, and streaming arriving late. 0 for a run whose change from frame to frame is exactly the
// reference's.
#include <cstddef>
#include <deque>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/render/image.h"
#include "sample_game/camera_path.h"
#include "splat_lod/eval/image_metrics.h"

namespace sample_game {

// Frames in the strip, and how many of them come before the frame that ends the worst pair.
inline constexpr std::size_t kStripFrames = 6;
inline constexpr std::size_t kStripFramesBefore = 3;  // f−3 .. f+2 around the pair (f−1, f)
inline constexpr int kStripThumbnailWidth = 320;
// The strip's error row shows |(M_f − M_{f−1}) − (R_f − R_{f−1})| times this (temporal_error's mean
// of 2–6 is then dark grey, and a pop of 64 or more white).
inline constexpr int kStripErrorGain = 4;
inline constexpr const char* kStripFileName = "frames_strip.png";

// Images in [0, 1] (FloatImage); throws engine::Error naming the mismatch when the sizes differ.
double temporal_error(const splat_lod::eval::FloatImage& previous, const splat_lod::eval::FloatImage& current,
                      const splat_lod::eval::FloatImage& reference_previous,
                      const splat_lod::eval::FloatImage& reference_current);

// The first frame of the strip that shows the pair ending at `frame`: kStripFramesBefore earlier,
// moved so that all kStripFrames frames lie on a path of `frames` frames.
std::size_t strip_start(std::size_t frame, std::size_t frames);

// Collects the strip while a run walks the path, keeping only the images it may still need: the
// last kStripFrames frames and the frames of the best window so far. The window is that of the
// frame with the largest temporal error (ties: the first); without any, the fallback window.
class StripRecorder {
public:
    // `frames`: the path's frame count; `fallback_start`: the first frame of the window kept when no
    // frame has a temporal error (the profile: the overview's first frame).
    StripRecorder(std::size_t frames, std::size_t fallback_start);

    // Each frame in order, with its segment and temporal error (negative: none).
    void add(int frame, Segment segment, const engine::Image& image, double temporal_error);

    // The frames kept for the strip, in order (kStripFrames once the run has passed the window).
    struct Frame {
        int frame = 0;
        Segment segment = Segment::ground;
        engine::Image image;
        double temporal_error = -1.0;
    };
    const std::vector<Frame>& window() const { return window_; }
    bool measured() const { return best_error_ >= 0.0; }  // false: the fallback window

    // Writes the strip (atomically) as PNG: the reference row (tiles of the window's frames that
    // have a reference, black elsewhere; left out when none has), the run's frames labelled with
    // their index, segment and temporal error, and the error row: for a frame whose predecessor has
    // a reference too, |(M_f − M_{f−1}) − (R_f − R_{f−1})| × kStripErrorGain, the change the reference
    // does not have (a pop shows as a bright patch; the camera's motion cancels), black elsewhere and
    // left out when no frame has one. A frame's change from the one before alone (|M_f − M_{f−1}|)
    // would not do: the path moves the camera far between frames, and that change fills the picture.
    // Returns false (and writes nothing) when no frame was kept. Throws engine::Error naming the file.
    bool write(const std::filesystem::path& path, const std::map<int, splat_lod::eval::FloatImage>& reference,
               int thumbnail_width = kStripThumbnailWidth) const;

private:
    std::size_t frames_;
    std::size_t window_start_;
    double best_error_ = -1.0;
    std::deque<Frame> recent_;  // the last kStripFrames frames
    std::vector<Frame> window_;
};

}  // namespace sample_game
