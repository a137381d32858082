// engine_render: renders a scene file to PNG, headless.
//   engine_render --scene content/scenes/helmet.json --out helmet.png [--width 960 --height 540]
//                 [--camera NODE | --eye X,Y,Z --target X,Y,Z [--up X,Y,Z] [--fov-y DEG]]
//                 [--plugin LIB.so ...] [--frames N] [--settle SECONDS] [--depth-png FILE] [--pick X,Y ...]
// Static plugins built with the engine (e.g. splat_lod) are always started; --plugin loads more.
// --settle: before the N frames, renders frames while a plugin reports background work
// (plugin_msgs::BackgroundWork: a drop-in LOD baking or importing a capture), printing its lines as they
// change, for at most SECONDS; the output is then the finished picture (an error if the work is not done).
// --depth-png: also writes the frame's view depth (engine::depth_image: grey by inverse depth) as the
// passes after the plugins see it: the meshes' depth merged with what plugins wrote (the splats' depth).
// --pick X,Y: what the last frame drew under pixel (X, Y) (engine/render/picking.h: the nearest mesh or
// the point where the splats' accumulated opacity first passes ½), printed with its node and world
// point, and marked in the output PNG with a cross (white on black). Repeatable.
// Prints the GL renderer and the per-pass CPU/GPU times of the last frame.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <utility>

#include <plugin_msgs/background_work.h>
#include <plugin_msgs/frame_statistics.h>
#include <CLI/CLI.hpp>

#include "engine/core/cli_values.h"
#include "engine/core/error.h"
#include "engine/engine.h"
#include "engine/platform/gl_context.h"
#include "engine/plugin/static_plugins.h"
#include "engine/render/image.h"
#include "engine/render/picking.h"
#include "engine/render/render_target.h"
#include "engine/render/renderer.h"
#include "engine/render/scene_camera.h"
#include "engine/scene/node.h"

namespace {

struct Options {
    std::string scene, out, camera_node, eye, target, up = "0,1,0", depth_png;
    std::vector<std::string> plugins, picks;
    int width = 960, height = 540, frames = 1;
    float fov_y_deg = 50.0f;
    double settle_seconds = 0.0;
};

engine::CameraView choose_camera(const engine::Scene& scene, const Options& o) {
    const float fov = glm::radians(o.fov_y_deg);
    if (!o.eye.empty() || !o.target.empty()) {
        if (o.eye.empty() || o.target.empty()) engine::fail("--eye and --target go together");
        const glm::vec3 eye = engine::parse_vec3(o.eye, "--eye"), target = engine::parse_vec3(o.target, "--target");
        const auto bounds = scene.world_bounds();
        const float reach = bounds ? glm::length(bounds->max - bounds->min) + glm::length(target - eye) : 1000.0f;
        return engine::make_look_at_camera(eye, target, engine::parse_vec3(o.up, "--up"), fov, o.width, o.height,
                                           std::max(reach * 1e-4f, 1e-3f), reach * 4.0f);
    }
    if (auto camera = engine::scene_camera(scene, o.camera_node, o.width, o.height)) return *camera;
    return engine::framing_camera(scene, o.width, o.height, fov);
}

// Renders frames while any plugin reports background work, at most `seconds`; throws when it is still
// going then. Prints each new set of lines with the time since the start.
void settle(engine::Engine& engine, const engine::Scene& scene, const engine::CameraView& camera,
            engine::RenderTarget& target, double seconds) {
    std::map<std::string, std::vector<std::string>> work;  // by source
    bool changed = false;
    const auto subscription =
        engine.bus().subscribe<plugin_msgs::BackgroundWork>([&](const plugin_msgs::BackgroundWork& w) {
            work[w.source] = w.lines;
            changed = true;
        });
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    for (int frame = 1;; ++frame) {
        engine.renderer().render(scene, camera, target);
        if (changed)
            for (const auto& [source, lines] : work)
                for (const auto& line : lines)
                    std::printf("  %7.1f s, frame %d: %s: %s\n", elapsed(), frame, source.c_str(), line.c_str());
        changed = false;
        std::fflush(stdout);  // progress, also when stdout is a file
        bool busy = false;
        for (const auto& [source, lines] : work) busy = busy || !lines.empty();
        if (!busy) {
            std::printf("settled after %d frames, %.1f s\n", frame, elapsed());
            return;
        }
        if (elapsed() > seconds)
            engine::fail("--settle " + std::to_string(seconds) + ": background work still running after " +
                         std::to_string(frame) + " frames");
    }
}

// A cross of 2·reach + 1 pixels centred on `p`, white with a black outline.
void mark(engine::Image& image, glm::ivec2 p, int reach) {
    const auto put = [&](int x, int y, std::uint8_t v) {
        if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
        std::uint8_t* q = image.pixel(x, y);
        q[0] = q[1] = q[2] = v;
    };
    for (const std::uint8_t v : {std::uint8_t{0}, std::uint8_t{255}})
        for (int d = -reach; d <= reach; ++d) {
            const int w = v == 0 ? 1 : 0;  // the outline one pixel wider
            for (int o = -w; o <= w; ++o) {
                put(p.x + d, p.y + o, v);
                put(p.x + o, p.y + d, v);
            }
        }
}

// Prints the answer of each --pick and marks its pixel in `image`.
void report_picks(engine::Engine& engine, const std::vector<std::pair<glm::ivec2, std::uint64_t>>& picks,
                  engine::Image& image) {
    for (const auto& [pixel, ticket] : picks) {
        const engine::PickResult result = engine.renderer().pick_result(ticket, true);
        if (!result.hit) {
            std::printf("pick %d,%d: nothing\n", pixel.x, pixel.y);
            continue;
        }
        const engine::PickHit& hit = *result.hit;
        std::printf("pick %d,%d: node '%s' (%s) at %.4f, %.4f, %.4f, depth %.4f\n", pixel.x, pixel.y,
                    hit.node->name().c_str(), std::string(hit.component->type_name()).c_str(), hit.position.x,
                    hit.position.y, hit.position.z, hit.depth);
        mark(image, pixel, std::max(3, image.height / 60));
    }
}

int run(const Options& o) {
    auto context = engine::HeadlessGlContext::create();
    engine::Engine engine;
    engine_add_static_plugins(engine.plugins());
    for (const auto& plugin : o.plugins) engine.plugins().load_shared(plugin);
    const auto scene = engine.load_scene(o.scene);
    const engine::CameraView camera = choose_camera(*scene, o);
    engine::RenderTarget target(o.width, o.height);
    if (o.settle_seconds > 0.0) settle(engine, *scene, camera, target, o.settle_seconds);
    std::vector<std::pair<glm::ivec2, std::uint64_t>> picks;
    for (int i = 0; i < o.frames; ++i) {
        if (i + 1 == o.frames)  // the last frame answers them, at most kMaxPicksPerFrame
            for (const auto& text : o.picks) {
                const glm::ivec2 p = engine::parse_pixel(text, "--pick");
                if (p.x >= o.width || p.y >= o.height)
                    engine::fail("--pick " + text + ": outside the " + std::to_string(o.width) + "x" +
                                 std::to_string(o.height) + " image");
                picks.emplace_back(p, engine.renderer().pick(p));
            }
        engine.renderer().render(*scene, camera, target);
    }
    engine::Image image = target.read_color();
    report_picks(engine, picks, image);
    engine::write_png(o.out, image);
    if (!o.depth_png.empty())
        engine::write_png(o.depth_png, engine::depth_image(target.read_view_depth(), o.width, o.height));

    engine.renderer().timers().wait_all();
    std::printf("%s: %dx%d on %s\n", o.out.c_str(), o.width, o.height, context->info().renderer.c_str());
    if (const auto stats = engine.bus().latest<plugin_msgs::FrameStatistics>()) {
        const auto& gpu = engine.renderer().timers().latest();
        for (const auto& pass : stats->passes) {
            double gpu_ms = pass.gpu_ms;
            if (gpu)
                for (const auto& span : *gpu)
                    if (span.name == pass.name) gpu_ms = span.milliseconds;
            std::printf("  pass %-12s cpu %8.2f ms  gpu %8.2f ms\n", pass.name.c_str(), pass.cpu_ms, gpu_ms);
        }
        std::printf("  frame        cpu %8.2f ms\n", stats->cpu_frame_ms);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Render a scene file to PNG (headless OpenGL)"};
    app.add_option("--scene", o.scene, "scene JSON file")->required();
    app.add_option("--out", o.out, "output PNG")->required();
    app.add_option("--width", o.width, "image width")->check(CLI::Range(1, 16384));
    app.add_option("--height", o.height, "image height")->check(CLI::Range(1, 16384));
    app.add_option("--camera", o.camera_node, "name of the node whose camera to use");
    app.add_option("--eye", o.eye, "look-at camera position X,Y,Z");
    app.add_option("--target", o.target, "look-at target X,Y,Z");
    app.add_option("--up", o.up, "look-at up vector X,Y,Z");
    app.add_option("--fov-y", o.fov_y_deg, "vertical field of view in degrees")->check(CLI::Range(1.0f, 179.0f));
    app.add_option("--plugin", o.plugins, "shared-library plugin to load (repeatable)");
    app.add_option("--frames", o.frames, "frames to render (timings are from the last)")->check(CLI::Range(1, 100000));
    app.add_option("--depth-png", o.depth_png, "also write the view depth (meshes and splats) as a grey PNG");
    app.add_option("--settle", o.settle_seconds,
                   "first render while plugins report background work (a drop-in LOD), at most this many seconds")
        ->check(CLI::Range(0.0, 1e6));
    app.add_option("--pick", o.picks, "print and mark what is under pixel X,Y (repeatable, at most 64)");
    CLI11_PARSE(app, argc, argv);
    if (o.picks.size() > engine::kMaxPicksPerFrame) {
        std::fprintf(stderr, "engine_render: at most %zu --pick\n", engine::kMaxPicksPerFrame);
        return 1;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "engine_render: %s\n", e.what());
        return 1;
    }
}
