#include "sample_game/harness/profile_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/engine.h"
#include "engine/render/render_target.h"
#include "formatted.h"
#include "progress.h"
#include "sample_game/game_world.h"
#include "sample_game/harness/chunk_borders.h"
#include "sample_game/harness/frame_probe.h"
#include "sample_game/harness/frame_sheet.h"
#include "sample_game/harness/frame_strip.h"
#include "sample_game/harness/profile_plots.h"
#include "sample_game/harness/reference_cache.h"
#include "sample_game/world_path.h"
#include "splat_lod/eval/image_metrics.h"
#include "splat_lod/eval/temporal_sweep.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"

namespace sample_game {
namespace {

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
// every K-th frame of the rest of the path (of the path's count), and the frames with a reference.
std::vector<std::size_t> baseline_frame_indices(const std::vector<PathPose>& poses, const ProfileOptions& o,
                                                const std::vector<std::size_t>& reference_frames) {
    std::set<std::size_t> chosen(reference_frames.begin(), reference_frames.end());
    std::size_t overview_seen = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        if (poses[i].segment == Segment::overview) {
            if (overview_seen++ % static_cast<std::size_t>(o.baseline_overview_every) == 0) chosen.insert(i);
        } else if (o.baseline_every > 0 && i % static_cast<std::size_t>(o.baseline_every) == 0) {
            chosen.insert(i);
        }
    }
    return {chosen.begin(), chosen.end()};
}

std::string frame_name(const std::string& run, const FrameRecord& r) {
    return formatted("%s_%04d_%s.png", run.c_str(), r.frame, std::string(to_string(r.segment)).c_str());
}

// A run's image of its last frame with a reference, for the temporal error of the frame after it.
struct PreviousImage {
    int frame = -1;
    splat_lod::eval::FloatImage image;
};

// The first frame of the overview: the strip's frames when there is no reference to choose them.
std::size_t overview_start(const std::vector<PathPose>& poses) {
    for (std::size_t i = 0; i < poses.size(); ++i)
        if (poses[i].segment == Segment::overview) return i;
    return 0;
}

struct Run {
    const ProfileOptions& options;
    engine::Engine& engine;
    GameWorld& world;
    const std::vector<PathPose>& poses;
    std::FILE* progress;
    FrameSheet sheet;
    std::vector<std::filesystem::path> frame_pictures;
    // The cached reference of this run's key (none: no reference columns) and what seam_ratio needs.
    const CachedReference* cached_reference = nullptr;
    std::unique_ptr<HeightGrid> ground;
    // The LOD run's consecutive frames around its largest temporal error (frames_strip.png).
    StripRecorder strip;
    PreviousImage previous_lod, previous_baseline;
    std::vector<std::size_t> reference_frames() const {
        std::vector<std::size_t> frames;
        if (cached_reference)
            for (const auto& [frame, image] : cached_reference->frames)
                frames.push_back(static_cast<std::size_t>(frame));
        return frames;
    }
    const splat_lod::eval::FloatImage* reference_of(int frame) const {
        if (!cached_reference) return nullptr;
        const auto it = cached_reference->frames.find(frame);
        return it == cached_reference->frames.end() ? nullptr : &it->second;
    }
    // This row's image against the reference, its seam_ratio (the baseline's tells how much of the
    // LOD's comes from what the borders happen to cross) and its temporal error against the run's
    // image of the frame before, when these frames have a reference.
    void compare_with_reference(const engine::Image& picture, const engine::CameraView& camera, FrameRecord& r,
                                PreviousImage& previous) {
        const splat_lod::eval::FloatImage* truth = reference_of(r.frame);
        if (!truth) return;
        auto image = splat_lod::eval::to_float(picture);
        r.psnr_vs_reference = splat_lod::eval::psnr(image, *truth);
        r.ssim_vs_reference = splat_lod::eval::ssim(image, *truth);
        if (!ground)
            ground = std::make_unique<HeightGrid>([&](float x, float z) { return world.ground().height(x, z); },
                                                  world.manifest().size_m);
        const ChunkMap map = chunk_map(*ground, chunk_grid(world.manifest()), camera);
        r.seam_ratio = seam_ratio(image, *truth, map).value_or(-1.0);
        r.seam_ratio_same_distance = seam_ratio_same_distance(image, *truth, map).value_or(-1.0);
        if (options.frames_png_every > 0)
            engine::write_png(options.out / "frames" / ("seams_" + frame_name(r.run, r)),
                              seam_picture(image, *truth, map));
        const splat_lod::eval::FloatImage* truth_before = reference_of(r.frame - 1);
        if (truth_before && previous.frame == r.frame - 1) {
            r.temporal_error = temporal_error(previous.image, image, *truth_before, *truth);
            r.pop = splat_lod::eval::temporal_pair_pop(previous.image, image, *truth_before, *truth);
        }
        previous = {r.frame, std::move(image)};
    }

    void keep_picture(const engine::Image& image, const FrameRecord& r) {
        if (options.frames_png_every <= 0 || r.frame % options.frames_png_every != 0) return;
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
            for (const std::size_t i : baseline_frame_indices(poses, options, reference_frames())) compared.insert(i);
        engine::RenderTarget target(options.width, options.height);
        std::vector<FrameRecord> records;
        Progress report(progress, "LOD + streaming: frame", poses.size());
        for (std::size_t i = 0; i < poses.size(); ++i) {
            FrameRecord r;
            r.frame = static_cast<int>(i);
            record_pose(world, poses[i], r);
            const engine::CameraView camera = world.camera(poses[i], options.width, options.height);
            r.stream_update_ms = world.update_streaming(camera, first_update + i, pose_velocity(poses, i));
            draw_and_measure(world, engine, camera, target, r);
            const engine::Image image = target.read_color();
            if (options.switch_pops && i > 0)
                measure_switch_pop(world, engine, camera, world.camera(poses[i - 1], options.width, options.height),
                                   image, target, r);
            if (options.stereo_ipd > 0.0f) measure_stereo(world, engine, camera, options.stereo_ipd, target, r);
            keep_picture(image, r);
            if (compared.count(i)) lod_images[r.frame] = image;
            compare_with_reference(image, camera, r, previous_lod);
            strip.add(r.frame, r.segment, image, r.temporal_error);
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
        lod.rule.mode = plugin_msgs::LodMode::baseline;
        lod.splat_budget = 0;  // the baseline draws everything, whatever the game's budget
        engine.bus().publish(lod);
        const std::vector<std::size_t> chosen = baseline_frame_indices(poses, options, reference_frames());
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
            record_pose(world, poses[chosen[k]], r);
            const engine::CameraView camera = world.camera(poses[chosen[k]], options.width, options.height);
            draw_and_measure(world, engine, camera, target, r);
            const engine::Image image = target.read_color();
            keep_picture(image, r);
            compare_with_reference(image, camera, r, previous_baseline);
            if (const auto it = lod_images.find(r.frame); it != lod_images.end()) {
                const auto reference = splat_lod::eval::to_float(image);
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

// `path_frames`: the poses walked (a --path file's own count, else --frames).
std::string describe_settings(const ProfileOptions& o, std::size_t path_frames) {
    const GameSettings& s = o.settings;
    return formatted(
        "%dx%d, %d path frames, LOD mode %s (S_T %.2f px, rel %.2f/%.2f, transition band %.4g octaves placed "
        "%s, overlapping levels' band %.4g), "
        "streamer fades over %d updates, cut anticipates %d, render scale %.3f (%s), "
        "memory budget %.0f MiB, upload budget %.2f MiB/frame, splat frame memory %s, load distance x%.2f, "
        "streaming %s, fov %.0f deg",
        o.width, o.height, static_cast<int>(path_frames), std::string(plugin_msgs::to_string(s.lod.rule.mode)).c_str(),
        s.lod.rule.size_threshold_px, s.lod.rule.rel_min, s.lod.rule.rel_max, s.lod.rule.transition_band,
        std::string(plugin_msgs::to_string(s.lod.rule.transition_placement)).c_str(),
        s.lod.rule.overlap_transition_band, s.fade_frames, s.anticipation_updates, s.lod.render_scale,
        std::string(plugin_msgs::to_string(s.lod.upscaler)).c_str(), mib(s.memory_budget_bytes),
        mib(s.upload_budget_bytes),
        s.frame_memory_bytes > 0 ? formatted("%.0f MiB", mib(s.frame_memory_bytes)).c_str() : "without a limit",
        s.load_distance_scale, s.sync_streaming ? "synchronous (--sync-streaming)" : "on the background thread",
        s.fov_y_deg);
}

// What an earlier run left in the output folder is removed first, so that nothing stale (a plot
// gnuplot could not redraw, frames of a longer path) is mistaken for this run's.
void remove_previous_outputs(const std::filesystem::path& out) {
    for (const char* name :
         {"profile.csv", "baseline.csv", "summary.txt", "frame_time.png", "memory.png", "gaussians.png",
          "frames_sheet.png", kStripFileName, "lod.dat", "baseline.dat", "plots.gp", "plots.log"})
        std::filesystem::remove(out / name);
    if (!std::filesystem::is_directory(out / "frames")) return;
    for (const auto& entry : std::filesystem::directory_iterator(out / "frames")) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() == ".png" &&
            (name.rfind("lod_", 0) == 0 || name.rfind("baseline_", 0) == 0 || name.rfind("seams_", 0) == 0))
            std::filesystem::remove(entry.path());
    }
}

// The baseline run (every chunk resident) and its CSV. `load_seconds` is how long loading every chunk
// took, `baseline_seconds` the rest: the baseline's frames.
std::vector<FrameRecord> baseline_run(const ProfileOptions& options, Run& run, double& load_seconds,
                                      double& baseline_seconds) {
    const auto baseline_start = Clock::now();
    std::vector<FrameRecord> baseline = run.baseline_frames(load_seconds);
    baseline_seconds = seconds_since(baseline_start) - load_seconds;
    write_frames_csv(options.out / "baseline.csv", baseline,
                     "sample_game profile, baseline (every chunk resident, mode baseline): " +
                         describe_settings(options, run.poses.size()));
    return baseline;
}

// The plots, the frame sheet and the frame strip; the files made go into outcome.pictures.
PlotResult write_pictures(const ProfileOptions& options, const std::vector<FrameRecord>& lod,
                          const std::vector<FrameRecord>& baseline, const Run& run, ProfileOutcome& outcome) {
    const PlotResult plots = write_profile_plots(options.out, lod, baseline, options.settings.memory_budget_bytes,
                                                 options.settings.upload_budget_bytes);
    outcome.plot_problem = plots.problem;
    outcome.pictures = plots.pictures;
    if (!run.sheet.empty()) {
        run.sheet.write(options.out / "frames_sheet.png");
        outcome.pictures.push_back(options.out / "frames_sheet.png");
    }
    static const std::map<int, splat_lod::eval::FloatImage> no_reference;
    if (run.strip.write(options.out / kStripFileName,
                        run.cached_reference ? run.cached_reference->frames : no_reference))
        outcome.pictures.push_back(options.out / kStripFileName);
    return plots;
}

// What the strip shows, for the summary's list of outputs.
std::string strip_note(const StripRecorder& strip) {
    const auto& frames = strip.window();
    if (frames.empty()) return "";
    std::string note = formatted("LOD frames %d..%d", frames.front().frame, frames.back().frame);
    if (!strip.measured()) return note + " (the overview's first; no reference, so no temporal_error to choose by)";
    const auto worst = std::max_element(
        frames.begin(), frames.end(), [](const auto& a, const auto& b) { return a.temporal_error < b.temporal_error; });
    return note + formatted(" around the largest temporal_error (frame %d: %.2f), the reference above", worst->frame,
                            worst->temporal_error);
}

std::string preload_note(const ProfileOptions& options, const PreloadStats& preload) {
    return options.preload ? formatted("; first view preloaded in %llu updates (%.1f MiB resident, %.0f s)",
                                       static_cast<unsigned long long>(preload.updates), mib(preload.resident_bytes),
                                       preload.seconds)
                           : std::string("; no preload (cold start)");
}

// With --switch-pops: the largest switch pop of the walk (and its frame) and the mean.
std::string switch_pop_note(const ProfileOptions& options, const std::vector<FrameRecord>& lod) {
    if (!options.switch_pops) return "";
    double peak = -1.0, sum = 0.0;
    int frame = -1, pairs = 0;
    for (const FrameRecord& r : lod) {
        if (r.switch_pop < 0.0) continue;
        sum += r.switch_pop;
        ++pairs;
        if (r.switch_pop > peak) peak = r.switch_pop, frame = r.frame;
    }
    return pairs == 0 ? std::string("; switch pops: no pair")
                      : formatted(
                            "; switch pop (this frame against it drawn with the frame before's selection, "
                            "99.9th percentile, 0..255) peak %.2f (frame %d), mean %.3f over %d pairs",
                            peak, frame, sum / pairs, pairs);
}

// With --stereo: per segment, the median of the frames' stereo-to-mono ratios, and the lowest eye PSNR.
std::string stereo_note(const ProfileOptions& options, const std::vector<FrameRecord>& lod) {
    if (!(options.stereo_ipd > 0.0f)) return "";
    std::map<std::string, std::vector<double>> ratios;
    double lowest = std::numeric_limits<double>::infinity();
    for (const FrameRecord& r : lod) {
        if (!(r.stereo_frame_ms > 0.0 && r.frame_ms > 0.0)) continue;
        ratios[std::string(to_string(r.segment))].push_back(r.stereo_frame_ms / r.frame_ms);
        lowest = std::min(lowest, r.stereo_eye_psnr);
    }
    std::string note = formatted("; stereo (ipd %.3f), the stereo frame over the mono one, median per segment:",
                                 static_cast<double>(options.stereo_ipd));
    for (auto& [segment, values] : ratios) {
        std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
        note += formatted(" %s %.3f", segment.c_str(), values[values.size() / 2]);
    }
    return note + formatted(", lowest eye PSNR against its own selection %.2f dB", lowest);
}

// The summary's list of what the run wrote, and why the plots are missing if they are.
std::vector<std::string> listed_outputs(const ProfileOptions& options,
                                        const std::vector<std::filesystem::path>& pictures, std::size_t frame_pictures,
                                        const std::string& plot_problem, const std::string& strip) {
    std::vector<std::string> outputs;
    const std::string folder = options.out.string();
    outputs.push_back(folder + "/profile.csv: one row per frame of the LOD run (columns in its # header)");
    if (options.baseline) outputs.push_back(folder + "/baseline.csv: the baseline's frames, same columns");
    for (const auto& picture : pictures)
        outputs.push_back(picture.filename() == kStripFileName ? picture.string() + ": " + strip : picture.string());
    if (frame_pictures > 0)
        outputs.push_back(formatted("%s/frames/: %zu frames (every %d-th)", folder.c_str(), frame_pictures,
                                    options.frames_png_every));
    if (!plot_problem.empty()) outputs.push_back("NO PLOTS: " + plot_problem);
    return outputs;
}

std::string reference_note(const ProfileOptions& options, const std::optional<CachedReference>& reference,
                           const ReferenceKey& key) {
    return reference
               ? formatted("found, %s (%zu frames, %dx supersampled)", reference->folder.string().c_str(),
                           reference->frames.size(), key.supersample)
               : formatted(
                     "none cached for this run (%s); `sample_game_harness --reference` with the same --world, "
                     "--width, --height, --frames and --fov-y makes it",
                     reference_folder(options.reference_world.empty() ? options.world : options.reference_world, key)
                         .string()
                         .c_str());
}

}  // namespace

void validate_path_run(const std::filesystem::path& world, int width, int height, int frames) {
    if (world.empty())
        engine::fail("sample_game_harness: --world is required (a folder holding world.json, made by splat_world)");
    if (width < 16 || height < 16 || width > 16384 || height > 16384)
        engine::fail("sample_game_harness: --width and --height must be 16..16384, got " + std::to_string(width) + "x" +
                     std::to_string(height));
    if (frames < 10)
        engine::fail(
            "sample_game_harness: --frames must be at least 10 (every segment of the path needs frames), got " +
            std::to_string(frames));
}

void validate(const ProfileOptions& o) {
    validate_path_run(o.world, o.width, o.height, o.frames);
    if (o.frames_png_every < 0) engine::fail("sample_game_harness: --frames-png must not be negative");
    if (o.baseline_every < 0) engine::fail("sample_game_harness: --baseline-every must not be negative");
    if (o.baseline_overview_every < 1)
        engine::fail("sample_game_harness: --baseline-overview-every must be at least 1");
    if (o.reference_supersample < 3 || o.reference_supersample > 8)
        engine::fail("sample_game_harness: --supersample must be 3..8, got " + std::to_string(o.reference_supersample));
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
    const std::vector<PathPose> poses = world.path(options.frames);
    world.warm_up(options.width, options.height);

    const std::filesystem::path& truth = options.reference_world.empty() ? options.world : options.reference_world;
    const ReferenceKey key = reference_key(truth, options.width, options.height, poses, options.settings.fov_y_deg,
                                           options.reference_supersample);
    const std::optional<CachedReference> reference = read_reference(truth, key);  // throws when broken

    Run run{options,  engine,
            world,    poses,
            progress, FrameSheet(240, 5),
            {},       reference ? &*reference : nullptr,
            nullptr,  StripRecorder(poses.size(), overview_start(poses)),
            {},       {},
            {}};
    const auto lod_start = Clock::now();
    PreloadStats preload;
    const std::vector<FrameRecord> lod = run.lod_frames(preload);
    const double lod_seconds = seconds_since(lod_start);
    write_frames_csv(options.out / "profile.csv", lod,
                     "sample_game profile, LOD + streaming: " + describe_settings(options, poses.size()));
    std::vector<FrameRecord> baseline;
    double load_seconds = 0.0, baseline_seconds = 0.0;
    if (options.baseline) baseline = baseline_run(options, run, load_seconds, baseline_seconds);

    ProfileOutcome outcome;
    const PlotResult plots = write_pictures(options, lod, baseline, run, outcome);
    outcome.summary =
        summarize(lod, baseline, options.settings.memory_budget_bytes, options.settings.upload_budget_bytes,
                  WorldScale{std::uint64_t(options.width) * std::uint64_t(options.height),
                             world.whole_world_gpu_bytes(), options.settings.lod.splat_budget});
    SummaryContext context;
    context.world = describe_world(options, world);
    context.settings = describe_settings(options, poses.size());
    context.wall_seconds = seconds_since(start);
    context.timing =
        formatted("LOD run %.0f s including the preload, loading every chunk %.0f s, baseline frames %.0f s",
                  lod_seconds, load_seconds, baseline_seconds);
    context.settings += preload_note(options, preload) + stereo_note(options, lod) + switch_pop_note(options, lod);
    context.outputs =
        listed_outputs(options, outcome.pictures, run.frame_pictures.size(), plots.problem, strip_note(run.strip));
    context.reference = reference_note(options, reference, key);
    outcome.summary_text = format_summary(outcome.summary, context);
    engine::write_text_file_atomic(options.out / "summary.txt", outcome.summary_text);
    return outcome;
}

}  // namespace sample_game
