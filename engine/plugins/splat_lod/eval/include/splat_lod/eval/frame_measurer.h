#pragma once
// Renders one camera with one method through the engine and measures it: the image, whole-frame
// wall time and per-pass GPU time medians over the timed frames (warm-up frames excluded), and
// the splat pass's statistics of the last frame.
#include <map>
#include <string>

#include "splat_lod/msgs/splat_statistics.h"

#include "engine/engine.h"
#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "splat_lod/eval/eval_method.h"
#include "splat_lod/splat_renderer.h"

namespace engine {
class RenderTarget;
}
namespace splat_lod::eval {

struct FrameMeasurement {
    engine::Image image;
    double wall_ms = 0.0;                  // median: render() to glFinish()
    std::map<std::string, double> gpu_ms;  // median per GPU timer span ("splat", "splat.sort", ...)
    plugin_msgs::SplatStatistics statistics;
};

class FrameMeasurer {
public:
    // The engine must have the splat_lod plugin started and a current GL context.
    FrameMeasurer(engine::Engine& engine, const engine::Scene& scene);

    // Warm-up frames first; frames whose key buffer overflowed (drawing fewer tile pairs than they
    // needed) are redrawn before timing starts, so every timed frame is complete.
    FrameMeasurement measure(const Method& method, const engine::CameraView& camera, int frames, int warmup);
    // One complete frame (no timing), for references.
    engine::Image render(const Method& method, const engine::CameraView& camera);

    // Another scene is measured with another measurer on the same engine.
    engine::Engine& engine() const { return engine_; }

private:
    double draw(const engine::CameraView& camera, engine::RenderTarget& target);
    void configure(const Method& method);
    void draw_until_complete(const engine::CameraView& camera, engine::RenderTarget& target);

    engine::Engine& engine_;
    const engine::Scene& scene_;
    SplatRenderer pass_;
};

double median(std::vector<double> values);

}  // namespace splat_lod::eval
