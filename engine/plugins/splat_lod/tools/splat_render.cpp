// splat_render: renders a splat file as stored (no axis flips) with a look-at camera, headless.
//   splat_render --in FILE --width W --height H --fov-y DEG --eye X,Y,Z --target X,Y,Z --up X,Y,Z
//                --out OUT.png [--background R,G,B] [--sh-degree N] [--frames N] [--mip-filter]
//                [--render-scale S --upscaler spline|bicubic|bilinear|lanczos3] [--tile 4|8|16]
//                [--low-res-tile 4|8|16] [--raster-fetch automatic|texel|shared] [--bbox-tiles] [--wide-sort-keys]
//                [--frame-memory-mib M] [--stereo [--ipd M]]
// Prints the Gaussians drawn and the per-pass GPU times (median over the frames after the first 2).
// --stereo: draws the left and right eyes of engine::stereo_eyes (one selection, the centre's) side by
// side into OUT.png (2W × H), and prints the stereo frame's time against the mono frame's, at the eye's
// size and at the pair's (2W × H, the same vertical field of view: a wider view), interleaved, medians
// over --frames, and each eye's PSNR against a mono render from that eye with its own selection.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

#include <plugin_msgs/frame_statistics.h>
#include <CLI/CLI.hpp>

#include "engine/core/cli_values.h"
#include "engine/core/error.h"
#include "engine/engine.h"
#include "engine/gl/gpu_timers.h"
#include "engine/platform/gl_context.h"
#include "engine/render/image.h"
#include "engine/render/render_target.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"

namespace {

struct Options {
    std::string in, out, eye, target, up = "0,1,0", background = "0,0,0";
    int width = 1280, height = 720, sh_degree = 3, frames = 1;
    float fov_y_deg = 50.0f;
    bool mip_filter = false;
    float render_scale = 1.0f;
    std::string upscaler = "spline";
    unsigned tile = 16, low_res_tile = 8;
    std::string raster_fetch = "automatic", gpu_storage = "compact";
    bool bbox_tiles = false, wide_sort_keys = false;
    std::string lod_mode = "full";
    float transition_band = plugin_msgs::LodRule::kDefaultTransitionBand;
    std::string transition_placement{plugin_msgs::to_string(plugin_msgs::LodRule{}.transition_placement)};
    float overlap_transition_band = plugin_msgs::LodRule::kDefaultOverlapTransitionBand;
    bool stereo = false;
    float ipd = 0.063f;
    double frame_memory_mib = 0.0;
};

void apply_settings(splat_lod::SplatPassSettings& settings, plugin_msgs::LodSettings& lod, const Options& o) {
    lod.mip_filter = o.mip_filter;
    lod.render_scale = o.render_scale;
    settings.tile_size = o.tile;
    settings.low_res_tile_size = o.low_res_tile;
    lod.upscaler = plugin_msgs::detail::enum_from_json<plugin_msgs::Upscaler>(plugin_msgs::kUpscalerNames, o.upscaler);
    settings.raster_fetch = o.raster_fetch == "texel"    ? splat_lod::RasterFetch::texel
                            : o.raster_fetch == "shared" ? splat_lod::RasterFetch::shared
                                                         : splat_lod::RasterFetch::automatic;
    settings.exact_tiles = !o.bbox_tiles;
    settings.gpu_storage = o.gpu_storage == "full" ? splat_lod::GpuStorage::full : splat_lod::GpuStorage::compact;
    settings.compact_sort_keys = !o.wide_sort_keys;
    settings.frame_memory_limit = static_cast<std::uint64_t>(o.frame_memory_mib * 1024.0 * 1024.0);
    lod.rule.mode = plugin_msgs::detail::enum_from_json<plugin_msgs::LodMode>(plugin_msgs::kLodModeNames, o.lod_mode);
    lod.rule.transition_band = o.transition_band;
    lod.rule.overlap_transition_band = o.overlap_transition_band;
    lod.rule.transition_placement = plugin_msgs::detail::enum_from_json<plugin_msgs::TransitionPlacement>(
        plugin_msgs::kTransitionPlacementNames, o.transition_placement);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// Milliseconds of drawing `views` one after the other, the GPU finished.
double frame_ms(engine::Engine& engine, const engine::Scene& scene,
                std::initializer_list<const engine::CameraView*> views, engine::RenderTarget& target) {
    const auto start = std::chrono::steady_clock::now();
    for (const engine::CameraView* view : views) engine.renderer().render(scene, *view, target);
    engine.renderer().timers().wait_all();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// --stereo: the pair side by side in `out`, its cost against the mono frame, each eye against a mono
// render from that eye with its own selection.
void run_stereo(engine::Engine& engine, const engine::Scene& scene, const engine::CameraView& centre,
                const engine::CameraView& wide, const Options& o) {
    const engine::StereoEyes eyes = engine::stereo_eyes(centre, o.ipd);
    engine::RenderTarget target(o.width, o.height);
    std::vector<engine::Image> images;
    for (const engine::CameraView* eye : {&eyes.left, &eyes.right}) {
        splat_lod::render_complete(engine, scene, *eye, target);
        images.push_back(target.read_color());
    }
    engine::write_png(o.out, engine::side_by_side(images[0], images[1]));
    double psnr[2];
    for (int k = 0; k < 2; ++k) {
        engine::CameraView own = k == 0 ? eyes.left : eyes.right;
        own.selection_view.reset();
        splat_lod::render_complete(engine, scene, own, target);
        psnr[k] = engine::compare_images(images[static_cast<std::size_t>(k)], target.read_color()).psnr_db;
    }
    // The mono frame at the eye's size, and at the pair's (2W × H, the same vertical field of view).
    engine::RenderTarget wide_target(wide.width, wide.height);
    std::vector<double> mono, mono_wide, stereo;
    frame_ms(engine, scene, {&centre}, target);  // warm
    splat_lod::render_complete(engine, scene, wide, wide_target);
    for (int i = 0; i < o.frames; ++i) {
        mono.push_back(frame_ms(engine, scene, {&centre}, target));
        stereo.push_back(frame_ms(engine, scene, {&eyes.left, &eyes.right}, target));
        mono_wide.push_back(frame_ms(engine, scene, {&wide}, wide_target));
    }
    std::printf(
        "stereo %dx%d per eye, ipd %.4f: stereo frame %.2f ms; mono frame %.2f ms (%.3fx), mono frame of "
        "the pair's size %dx%d %.2f ms (%.3fx); medians of %d\n",
        o.width, o.height, static_cast<double>(o.ipd), median(stereo), median(mono), median(stereo) / median(mono),
        wide.width, wide.height, median(mono_wide), median(stereo) / median(mono_wide), o.frames);
    std::printf("  each eye against a mono render from that eye with its own selection: left %.2f dB, right %.2f dB\n",
                psnr[0], psnr[1]);
}

int run(const Options& o) {
    auto context = engine::HeadlessGlContext::create();
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    splat_lod::LoadReport report;
    auto cloud = std::make_shared<const splat_lod::SplatCloud>(splat_lod::load_splat_file(o.in, &report));

    engine::Scene scene;
    scene.background = engine::parse_vec3(o.background, "--background");
    auto splat = std::make_unique<splat_lod::SplatComponent>();
    splat->asset = o.in;
    splat->cloud = cloud;
    splat->sh_degree_cap = o.sh_degree;
    scene.root().add_child("splats").attach(std::move(splat));

    const glm::vec3 eye = engine::parse_vec3(o.eye, "--eye"), target = engine::parse_vec3(o.target, "--target");
    const auto camera = engine::make_look_at_camera(eye, target, engine::parse_vec3(o.up, "--up"),
                                                    glm::radians(o.fov_y_deg), o.width, o.height, 0.01f, 1e6f);
    splat_lod::SplatRenderer pass(engine.renderer());
    plugin_msgs::LodSettings lod;
    apply_settings(pass.settings(), lod, o);
    engine.bus().publish(lod);
    if (o.stereo) {
        run_stereo(engine, scene, camera,
                   engine::make_look_at_camera(eye, target, engine::parse_vec3(o.up, "--up"), glm::radians(o.fov_y_deg),
                                               2 * o.width, o.height, 0.01f, 1e6f),
                   o);
        return 0;
    }
    engine::RenderTarget target_image(o.width, o.height);

    // Warm-up: the first frame compiles shaders and sizes the key buffer; the second is a plain one.
    splat_lod::render_complete(engine, scene, camera, target_image);
    engine.renderer().render(scene, camera, target_image);
    std::map<std::string, std::vector<double>> gpu_ms;
    for (int i = 0; i < o.frames; ++i) {
        engine.renderer().render(scene, camera, target_image);
        engine.renderer().timers().wait_all();
        const auto spans = engine.renderer().timers().latest().value_or(std::vector<engine::gl::GpuSpan>{});
        for (const auto& [name, ms] : engine::gl::span_totals(spans)) gpu_ms[name].push_back(ms);
    }
    pass.wait_for_statistics(engine.bus());
    engine::write_png(o.out, target_image.read_color());

    const auto& s = *pass.latest_statistics();
    std::printf("%s: %zu Gaussians (%s, SH degree %d, %zu dropped) -> %s %dx%d on %s\n", o.in.c_str(), cloud->size(),
                report.format.c_str(), cloud->sh_degree, report.dropped(), o.out.c_str(), o.width, o.height,
                context->info().renderer.c_str());
    const splat_lod::SplatMemory memory = pass.memory();
    std::printf(
        "  visible %llu, tile-splat pairs %llu (capacity %llu), GPU memory %.1f MiB (frame %.1f MiB, %u "
        "strip%s), raster fetch %s\n",
        static_cast<unsigned long long>(s.visible), static_cast<unsigned long long>(s.tile_splat_pairs),
        static_cast<unsigned long long>(s.key_capacity), static_cast<double>(s.resident_bytes) / (1 << 20),
        static_cast<double>(memory.frame_bytes) / (1 << 20), memory.strips, memory.strips == 1 ? "" : "s",
        splat_lod::to_string(pass.raster_fetch_in_use()));
    for (const auto& [name, times] : gpu_ms) std::printf("  gpu %-16s %9.2f ms\n", name.c_str(), median(times));
    return 0;
}

// The file, the image and the camera.
void add_view_options(CLI::App& app, Options& o) {
    app.add_option("--in", o.in,
                   "splat file (.ply, .compressed.ply, .splat, .spz, SOG meta.json, .glb, .gltf), a streamed SOG "
                   "lod-meta.json[#level], or a folder or .txt list of tiles")
        ->required();
    app.add_option("--out", o.out, "output PNG")->required();
    app.add_option("--width", o.width, "image width")->check(CLI::Range(1, 16384));
    app.add_option("--height", o.height, "image height")->check(CLI::Range(1, 16384));
    app.add_option("--fov-y", o.fov_y_deg, "vertical field of view, degrees")->check(CLI::Range(1.0f, 179.0f));
    app.add_option("--eye", o.eye, "camera position X,Y,Z")->required();
    app.add_option("--target", o.target, "look-at point X,Y,Z")->required();
    app.add_option("--up", o.up, "up vector X,Y,Z");
    app.add_option("--background", o.background, "background colour R,G,B in [0,1]");
    app.add_option("--sh-degree", o.sh_degree, "SH degree cap")->check(CLI::Range(0, 3));
    app.add_option("--frames", o.frames, "frames to time (after 2 warm-up frames)")->check(CLI::Range(1, 10000));
    app.add_flag("--mip-filter", o.mip_filter, "apply the optional 2D mip filter");
    app.add_option("--render-scale", o.render_scale, "rasterise splats at this fraction of the size and upscale")
        ->check(CLI::Range(1e-3f, 1.0f));
    app.add_option("--upscaler", o.upscaler, "spline, bicubic, bilinear or lanczos3")
        ->check(CLI::IsMember({"spline", "bicubic", "bilinear", "lanczos3"}));
    app.add_option("--tile", o.tile, "raster tile side at render scale 1")->check(CLI::IsMember({4u, 8u, 16u}));
    app.add_option("--low-res-tile", o.low_res_tile, "raster tile side below render scale 1")
        ->check(CLI::IsMember({4u, 8u, 16u}));
}

// Which Gaussians a baked file draws, and how they fade at the rule's switches.
void add_lod_options(CLI::App& app, Options& o) {
    app.add_option("--lod-mode", o.lod_mode, "LOD selection of a baked file (plugin_msgs::LodMode)")
        ->check(CLI::IsMember(
            std::vector<std::string>(plugin_msgs::kLodModeNames.begin(), plugin_msgs::kLodModeNames.end())))
        ->capture_default_str();
    app.add_option("--transition-band", o.transition_band,
                   "mode full: octaves of coverage over which a Gaussian fades into its coarser level (0: hard)")
        ->check(CLI::Range(0.0f, plugin_msgs::LodRule::kMaxTransitionBand))
        ->capture_default_str();
    app.add_option("--transition-placement", o.transition_placement,
                   "mode full: where each fade lies against its switch: before, inside (the hard rule's ranges), "
                   "centred, or auto (inside with --overlap-transition-band for a bake whose levels overlap, "
                   "centred with --transition-band for abutting levels, before with it for a file that does not say)")
        ->check(CLI::IsMember(std::vector<std::string>(plugin_msgs::kTransitionPlacementNames.begin(),
                                                       plugin_msgs::kTransitionPlacementNames.end())))
        ->capture_default_str();
    app.add_option("--overlap-transition-band", o.overlap_transition_band,
                   "mode full, placement auto: the band of a bake whose levels overlap at their switches")
        ->check(CLI::Range(0.0f, plugin_msgs::LodRule::kMaxTransitionBand))
        ->capture_default_str();
}

// How the splat pass stores, bins and rasterises them, and stereo.
void add_raster_options(CLI::App& app, Options& o) {
    app.add_option("--raster-fetch", o.raster_fetch, "how the raster reads splats: automatic, texel or shared")
        ->check(CLI::IsMember({"automatic", "texel", "shared"}));
    app.add_option("--gpu-storage", o.gpu_storage, "how the GPU stores Gaussians: compact or full (floats)")
        ->check(CLI::IsMember({"compact", "full"}));
    app.add_flag("--bbox-tiles", o.bbox_tiles, "bin splats into every tile of their bounding box (to measure)");
    app.add_flag("--wide-sort-keys", o.wide_sort_keys, "sort (depth bits, tile) key pairs (to measure)");
    app.add_option("--frame-memory-mib", o.frame_memory_mib,
                   "GPU memory the per-frame splat buffers may take; more is drawn in strips (0: no limit)")
        ->check(CLI::Range(0.0, 1e6));
    app.add_flag("--stereo", o.stereo, "draw both eyes side by side and compare the stereo frame with the mono one");
    app.add_option("--ipd", o.ipd, "with --stereo: the distance between the eyes, in the scene's units")
        ->check(CLI::Range(0.0f, 1e6f));
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Render a Gaussian splat file to PNG (headless OpenGL compute)"};
    add_view_options(app, o);
    add_lod_options(app, o);
    add_raster_options(app, o);
    CLI11_PARSE(app, argc, argv);
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "splat_render: %s\n", e.what());
        return 1;
    }
}
