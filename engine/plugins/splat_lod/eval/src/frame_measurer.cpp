#include "splat_lod/eval/frame_measurer.h"

#include <algorithm>
#include <chrono>

#include "engine/core/error.h"
#include "engine/gl/compute_step.h"
#include "engine/gl/gpu_timers.h"
#include "engine/render/render_target.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"

namespace splat_lod::eval {
namespace {
// The key buffer grows after each overflowing frame; a few redraws always suffice in practice.
constexpr int kMaxRedraws = 16;
}  // namespace

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

FrameMeasurer::FrameMeasurer(engine::Engine& engine, const engine::Scene& scene)
    : engine_(engine), scene_(scene), pass_(engine.renderer()) {}

void FrameMeasurer::configure(const Method& method) {
    SplatPassSettings settings;
    plugin_msgs::LodSettings lod;
    method.configure(lod, settings);
    pass_.settings() = settings;
    engine_.bus().publish(lod);  // the one way LOD settings reach the pass
}

// Wall time of one frame: the CPU recording plus the GPU work, closed by engine::gl::finish() so that the
// time includes the frame's execution (llvmpipe runs it on the CPU threads).
double FrameMeasurer::draw(const engine::CameraView& camera, engine::RenderTarget& target) {
    const auto start = std::chrono::steady_clock::now();
    engine_.renderer().render(scene_, camera, target);
    engine::gl::finish();
    const auto stop = std::chrono::steady_clock::now();
    engine_.renderer().timers().wait_all();
    pass_.wait_for_statistics(engine_.bus());
    return std::chrono::duration<double, std::milli>(stop - start).count();
}

void FrameMeasurer::draw_until_complete(const engine::CameraView& camera, engine::RenderTarget& target) {
    render_complete(engine_, scene_, camera, target, kMaxRedraws);
}

engine::Image FrameMeasurer::render(const Method& method, const engine::CameraView& camera) {
    configure(method);
    engine::RenderTarget target(camera.width, camera.height);
    draw_until_complete(camera, target);
    return target.read_color();
}

FrameMeasurement FrameMeasurer::measure(const Method& method, const engine::CameraView& camera, int frames,
                                        int warmup) {
    configure(method);
    engine::RenderTarget target(camera.width, camera.height);
    for (int i = 0; i < warmup; ++i) draw(camera, target);
    draw_until_complete(camera, target);

    FrameMeasurement m;
    std::vector<double> wall;
    std::map<std::string, std::vector<double>> gpu;
    for (int i = 0; i < frames; ++i) {
        wall.push_back(draw(camera, target));
        if (pass_.latest_statistics() && pass_.latest_statistics()->overflowed)
            engine::fail("splat_lod::eval::FrameMeasurer: a timed frame overflowed the key buffer");
        const auto spans = engine_.renderer().timers().latest().value_or(std::vector<engine::gl::GpuSpan>{});
        for (const auto& [name, ms] : engine::gl::span_totals(spans)) gpu[name].push_back(ms);
    }
    m.wall_ms = median(wall);
    for (const auto& [name, times] : gpu) m.gpu_ms[name] = median(times);
    if (pass_.latest_statistics()) m.statistics = *pass_.latest_statistics();
    m.image = target.read_color();
    return m;
}

}  // namespace splat_lod::eval
