#include "sample_game/profile_run.h"

#include <chrono>
#include <cmath>
#include <map>
#include <set>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/engine.h"
#include "engine/render/render_target.h"
#include "formatted.h"
#include "passes/splat_pass.h"
#include "sample_game/frame_probe.h"
#include "sample_game/frame_sheet.h"
#include "sample_game/game_world.h"
#include "sample_game/profile_plots.h"
#include "sample_game/world_path.h"
#include "splat_lod/eval/image_metrics.h"
#include "splat_lod/splat_lod_plugin.h"

namespace sample_game {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string duration(double seconds) {
    const auto s = static_cast<long long>(std::max(0.0, seconds) + 0.5);
    char text[32];
    if (s >= 60)
        std::snprintf(text, sizeof text, "%lldm%02llds", s / 60, s % 60);
    else
        std::snprintf(text, sizeof text, "%llds", s);
    return text;
}

double mib(std::uint64_t bytes) {
    return static_cast<double>(bytes) / static_cast<double>(kMiB);
}

// The preload stops after this many updates even if the first view is not complete by then.
constexpr std::uint64_t kMaxPreloadUpdates = 2000;

struct PreloadStats {
    std::uint64_t updates = 0, bytes = 0, resident_bytes = 0;
    double seconds = 0.0;
};

// The path frames the baseline draws: every K-th overview frame (of the overview's own count) and
// every K-th frame of the rest of the path (of the path's count).
std::vector<std::size_t> baseline_frame_indices(const std::vector<PathPose>& poses, const ProfileOptions& o) {
    std::vector<std::size_t> chosen;
    std::size_t overview_seen = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        if (poses[i].segment == Segment::overview) {
            if (overview_seen++ % static_cast<std::size_t>(o.baseline_overview_every) == 0) chosen.push_back(i);
        } else if (o.baseline_every > 0 && i % static_cast<std::size_t>(o.baseline_every) == 0) {
            chosen.push_back(i);
        }
    }
    return chosen;
}

// One line per step at most every two seconds (and always the last), with the time per step and
// what is left.
class Progress {
public:
    // total 0: open-ended (no ETA).
    Progress(std::FILE* out, std::string stage, std::size_t total)
        : out_(out), stage_(std::move(stage)), total_(total) {}
    void step(std::size_t done, const std::string& detail) {
        if (!out_ || (done == 0 && total_ > 0)) return;
        const auto now = Clock::now();
        if ((total_ == 0 || done < total_) && now - last_ < std::chrono::seconds(2)) return;
        last_ = now;
        const double elapsed = seconds_since(start_);
        if (total_ == 0) {  // open-ended: no ETA
            std::fprintf(out_, "sample_game: %s %zu%s, %s elapsed\n", stage_.c_str(), done, detail.c_str(),
                         duration(elapsed).c_str());
            std::fflush(out_);
            return;
        }
        const double per = done > 0 ? elapsed / static_cast<double>(done) : 0.0;
        std::fprintf(out_, "sample_game: %s %zu/%zu%s, %.2f s each, %s elapsed, ETA %s\n", stage_.c_str(), done, total_,
                     detail.c_str(), per, duration(elapsed).c_str(),
                     duration(per * static_cast<double>(total_ - done)).c_str());
        std::fflush(out_);
    }

private:
    std::FILE* out_;
    std::string stage_;
    std::size_t total_;
    Clock::time_point start_ = Clock::now(), last_{};
};

std::string frame_name(const std::string& run, const FrameRecord& r) {
    return formatted("%s_%04d_%s.png", run.c_str(), r.frame, std::string(to_string(r.segment)).c_str());
}

struct Run {
    const ProfileOptions& options;
    engine::Engine& engine;
    GameWorld& world;
    const std::vector<PathPose>& poses;
    std::FILE* progress;
    FrameSheet sheet;
    std::vector<std::filesystem::path> frame_pictures;

    void keep_picture(const engine::RenderTarget& target, const FrameRecord& r) {
        if (options.frames_png_every <= 0 || r.frame % options.frames_png_every != 0) return;
        const engine::Image image = target.read_color();
        const auto path = options.out / "frames" / frame_name(r.run, r);
        engine::write_png(path, image);
        frame_pictures.push_back(path);
        sheet.add(image, formatted("%s f%d %s", r.run == "lod" ? "LOD" : "baseline", r.frame,
                                   std::string(to_string(r.segment)).c_str()));
    }

    // Streams the first view until nothing is missing or in flight for a few updates (or the
    // memory budget stops it), drawing each update small so that the GPU scene takes its parts as
    // it would in the walk. Returns the updates used; the walk's streaming frames continue after.
    std::uint64_t preload(PreloadStats& stats) {
        const auto start = Clock::now();
        const int small_w = std::max(16, options.width / 4), small_h = std::max(16, options.height / 4);
        engine::RenderTarget small(small_w, small_h);
        const engine::CameraView camera = world.camera(poses.front(), options.width, options.height);
        const engine::CameraView small_camera = world.camera(poses.front(), small_w, small_h);
        Progress report(progress, "preloading the first view: update", 0);
        std::uint64_t update = 0;
        for (int quiet = 0; update < kMaxPreloadUpdates && quiet < 3; ++update) {
            world.update_streaming(camera, update);
            world.streamer().wait_idle();
            engine.renderer().render(world.scene(), small_camera, small);
            const std::uint64_t uploaded = world.streamer().stats().uploaded_bytes_last_update;
            const ChunkCensus census = world.census();
            stats.bytes += uploaded;
            quiet = uploaded == 0 && census.requested == 0 && census.loaded == 0 && census.partial == 0 ? quiet + 1 : 0;
            report.step(update + 1, formatted(" (%.1f MiB resident, %u of %zu chunks complete)",
                                              mib(world.streamer().resident_bytes()), census.resident,
                                              world.manifest().chunks.size()));
        }
        engine.renderer().timers().wait_all();
        world.pass().wait_for_statistics(engine.bus());
        stats.updates = update;
        stats.seconds = seconds_since(start);
        stats.resident_bytes = world.streamer().resident_bytes();
        return update;
    }

    // The LOD run's images of the frames the baseline draws too, to measure what LOD and streaming
    // cost in image quality (the baseline frame, every chunk resident, is the reference).
    std::map<int, engine::Image> lod_images;

    std::vector<FrameRecord> lod_frames(PreloadStats& preload_stats) {
        const std::uint64_t first_update = options.preload ? preload(preload_stats) : 0;
        std::set<std::size_t> compared;
        if (options.baseline)
            for (const std::size_t i : baseline_frame_indices(poses, options)) compared.insert(i);
        engine::RenderTarget target(options.width, options.height);
        std::vector<FrameRecord> records;
        Progress report(progress, "LOD + streaming: frame", poses.size());
        for (std::size_t i = 0; i < poses.size(); ++i) {
            FrameRecord r;
            r.frame = static_cast<int>(i);
            const engine::CameraView camera = world.camera(poses[i], options.width, options.height, &r);
            r.stream_update_ms = world.update_streaming(camera, first_update + i);
            draw_and_measure(world, engine, camera, target, r);
            keep_picture(target, r);
            if (compared.count(i)) lod_images[r.frame] = target.read_color();
            records.push_back(r);
            report.step(i + 1, formatted(" (%s, %.0f ms, %.1f MiB resident)", std::string(to_string(r.segment)).c_str(),
                                         r.frame_ms, mib(r.resident_bytes)));
        }
        return records;
    }

    std::vector<FrameRecord> baseline_frames(double& load_seconds) {
        Progress loading(progress, "baseline: chunks loaded", world.manifest().chunks.size());
        load_seconds = world.load_whole_world([&](std::size_t done, std::size_t) { loading.step(done, ""); });
        plugin_msgs::LodSettings lod = world.settings().lod;
        lod.mode = plugin_msgs::LodMode::baseline;
        engine.bus().publish(lod);
        const std::vector<std::size_t> chosen = baseline_frame_indices(poses, options);
        engine::RenderTarget target(options.width, options.height);
        std::vector<FrameRecord> records;
        if (chosen.empty()) return records;
        // The first draw uploads the whole world to the GPU scene; it is not a frame of the walk.
        const auto upload_start = Clock::now();
        splat_lod::render_complete(engine, world.scene(),
                                   world.camera(poses[chosen.front()], options.width, options.height), target,
                                   kMaxRedraws);
        load_seconds += seconds_since(upload_start);
        Progress report(progress, "baseline: frame", chosen.size());
        for (std::size_t k = 0; k < chosen.size(); ++k) {
            FrameRecord r;
            r.run = "baseline";
            r.frame = static_cast<int>(chosen[k]);
            const engine::CameraView camera = world.camera(poses[chosen[k]], options.width, options.height, &r);
            draw_and_measure(world, engine, camera, target, r);
            keep_picture(target, r);
            if (const auto it = lod_images.find(r.frame); it != lod_images.end()) {
                const auto reference = splat_lod::eval::to_float(target.read_color());
                const auto lod_image = splat_lod::eval::to_float(it->second);
                r.psnr_lod_vs_baseline = splat_lod::eval::psnr(lod_image, reference);
                r.ssim_lod_vs_baseline = splat_lod::eval::ssim(lod_image, reference);
            }
            records.push_back(r);
            report.step(k + 1, formatted(" (path frame %d, %s, %.0f ms)", r.frame,
                                         std::string(to_string(r.segment)).c_str(), r.frame_ms));
        }
        world.publish_lod_settings();  // back to the game's own mode
        return records;
    }
};

std::string describe_world(const ProfileOptions& o, const GameWorld& world) {
    const auto& m = world.manifest();
    return formatted(
        "%s: %.0f m, %zu chunks of %.0f m, %.2fM Gaussians (%.0f MiB on the GPU with every level resident), %zu props",
        o.world.string().c_str(), m.size_m, m.chunks.size(), m.chunk_size_m, static_cast<double>(m.gaussians) / 1e6,
        mib(world.whole_world_gpu_bytes()), m.props.size());
}

std::string describe_settings(const ProfileOptions& o) {
    const GameSettings& s = o.settings;
    return formatted(
        "%dx%d, %d path frames, LOD mode %s (S_T %.2f px, rel %.2f/%.2f), render scale %.3f (%s), "
        "memory budget %.0f MiB, upload budget %.2f MiB/frame, load distance x%.2f, streaming %s, fov %.0f deg",
        o.width, o.height, o.frames, std::string(plugin_msgs::to_string(s.lod.mode)).c_str(), s.lod.size_threshold_px,
        s.lod.rel_min, s.lod.rel_max, s.lod.render_scale, std::string(plugin_msgs::to_string(s.lod.upscaler)).c_str(),
        mib(s.memory_budget_bytes), mib(s.upload_budget_bytes), s.load_distance_scale,
        s.sync_streaming ? "synchronous (--sync-streaming)" : "on the background thread", s.fov_y_deg);
}

// What an earlier run left in the output folder is removed first, so that nothing stale (a plot
// gnuplot could not redraw, frames of a longer path) is mistaken for this run's.
void remove_previous_outputs(const std::filesystem::path& out) {
    for (const char* name : {"profile.csv", "baseline.csv", "summary.txt", "frame_time.png", "memory.png",
                             "gaussians.png", "frames_sheet.png", "lod.dat", "baseline.dat", "plots.gp", "plots.log"})
        std::filesystem::remove(out / name);
    if (!std::filesystem::is_directory(out / "frames")) return;
    for (const auto& entry : std::filesystem::directory_iterator(out / "frames")) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() == ".png" && (name.rfind("lod_", 0) == 0 || name.rfind("baseline_", 0) == 0))
            std::filesystem::remove(entry.path());
    }
}

}  // namespace

void validate(const ProfileOptions& o) {
    if (o.world.empty())
        engine::fail("sample_game: --world is required (a folder holding world.json, made by splat_world)");
    if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
        engine::fail("sample_game: --width and --height must be 16..16384, got " + std::to_string(o.width) + "x" +
                     std::to_string(o.height));
    if (o.frames < 10)
        engine::fail("sample_game: --frames must be at least 10 (every segment of the path needs frames), got " +
                     std::to_string(o.frames));
    if (o.frames_png_every < 0) engine::fail("sample_game: --frames-png must not be negative");
    if (o.baseline_every < 0) engine::fail("sample_game: --baseline-every must not be negative");
    if (o.baseline_overview_every < 1) engine::fail("sample_game: --baseline-overview-every must be at least 1");
    validate(o.settings);
    require_world_folder(o.world);
}

ProfileOutcome run_profile(const ProfileOptions& options, std::FILE* progress) {
    validate(options);
    const auto start = Clock::now();
    std::filesystem::create_directories(options.out);
    remove_previous_outputs(options.out);
    if (options.frames_png_every > 0) std::filesystem::create_directories(options.out / "frames");
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    GameWorld world(engine, options.world, options.settings);
    const std::vector<PathPose> poses = sample_world_path(world.terrain(), options.frames);
    world.warm_up(options.width, options.height);

    Run run{options, engine, world, poses, progress, FrameSheet(240, 5), {}, {}};
    const auto lod_start = Clock::now();
    PreloadStats preload;
    const std::vector<FrameRecord> lod = run.lod_frames(preload);
    const double lod_seconds = seconds_since(lod_start);
    write_frames_csv(options.out / "profile.csv", lod,
                     "sample_game profile, LOD + streaming: " + describe_settings(options));
    std::vector<FrameRecord> baseline;
    double load_seconds = 0.0, baseline_seconds = 0.0;
    if (options.baseline) {
        const auto baseline_start = Clock::now();
        baseline = run.baseline_frames(load_seconds);
        baseline_seconds = seconds_since(baseline_start) - load_seconds;
        write_frames_csv(
            options.out / "baseline.csv", baseline,
            "sample_game profile, baseline (every chunk resident, mode baseline): " + describe_settings(options));
    }

    ProfileOutcome outcome;
    const PlotResult plots = write_profile_plots(options.out, lod, baseline, options.settings.memory_budget_bytes,
                                                 options.settings.upload_budget_bytes);
    outcome.plot_problem = plots.problem;
    outcome.pictures = plots.pictures;
    if (!run.sheet.empty()) {
        run.sheet.write(options.out / "frames_sheet.png");
        outcome.pictures.push_back(options.out / "frames_sheet.png");
    }
    outcome.summary =
        summarize(lod, baseline, options.settings.memory_budget_bytes, options.settings.upload_budget_bytes);
    SummaryContext context;
    context.world = describe_world(options, world);
    context.settings = describe_settings(options);
    context.wall_seconds = seconds_since(start);
    context.timing =
        formatted("LOD run %.0f s including the preload, loading every chunk %.0f s, baseline frames %.0f s",
                  lod_seconds, load_seconds, baseline_seconds);
    context.settings +=
        options.preload
            ? formatted("; first view preloaded in %llu updates (%.1f MiB resident, %.0f s)",
                        static_cast<unsigned long long>(preload.updates), mib(preload.resident_bytes), preload.seconds)
            : std::string("; no preload (cold start)");
    const std::string folder = options.out.string();
    context.outputs.push_back(folder + "/profile.csv: one row per frame of the LOD run (columns in its # header)");
    if (options.baseline) context.outputs.push_back(folder + "/baseline.csv: the baseline's frames, same columns");
    for (const auto& picture : outcome.pictures) context.outputs.push_back(picture.string());
    if (!run.frame_pictures.empty())
        context.outputs.push_back(formatted("%s/frames/: %zu frames (every %d-th)", folder.c_str(),
                                            run.frame_pictures.size(), options.frames_png_every));
    if (!plots.problem.empty()) context.outputs.push_back("NO PLOTS: " + plots.problem);
    outcome.summary_text = format_summary(outcome.summary, context);
    engine::write_text_file_atomic(options.out / "summary.txt", outcome.summary_text);
    return outcome;
}

}  // namespace sample_game
