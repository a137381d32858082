#include "sample_game/soak_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/core/gnuplot.h"
#include "engine/core/process_memory.h"
#include "engine/engine.h"
#include "engine/gl/gl_census.h"
#include "engine/render/render_target.h"
#include "formatted.h"
#include "splat_lod/splat_renderer.h"
#include "sample_game/chunk_faults.h"
#include "sample_game/game_world.h"
#include "sample_game/world_path.h"
#include "splat_lod/eval/image_metrics.h"
#include "splat_lod/splat_lod_plugin.h"

namespace sample_game {
namespace {

using Clock = std::chrono::steady_clock;

// A lap end stops settling after this many updates even if reads are still going on.
constexpr std::uint32_t kMaxSettleUpdates = 400;
constexpr int kMaxRetryFrames = 300;
constexpr std::uint64_t kGlBytesSlack = kMiB, kRssSlack = 16 * kMiB;
constexpr double kGlBytesShare = 0.0, kRssShare = 0.02, kStreamedShare = 0.01, kMinPsnr = 40.0;
constexpr double kFaultStart = 0.45;  // of each faulted lap; the faults last until the walk ends

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

double mib(std::uint64_t bytes) {
    return static_cast<double>(bytes) / static_cast<double>(kMiB);
}

struct Sample {
    int lap = 0;
    std::uint64_t frame = 0;
    bool lap_end = false;
    bool faults_active = false;
    engine::gl::GlCensus gl;
    std::uint64_t rss = 0, streamed = 0;
    std::uint32_t failed_chunks = 0, resident_chunks = 0;
    std::uint64_t failed_events = 0;
};

std::string csv_row(const Sample& s) {
    return formatted("%d,%llu,%d,%d,%u,%u,%u,%u,%u,%u,%.3f,%.3f,%.3f,%.3f,%u,%u,%llu\n", s.lap,
                     static_cast<unsigned long long>(s.frame), s.lap_end ? 1 : 0, s.faults_active ? 1 : 0,
                     s.gl.objects(), s.gl.buffers, s.gl.textures, s.gl.vertex_arrays + s.gl.framebuffers,
                     s.gl.programs + s.gl.shaders, s.gl.samplers + s.gl.queries, mib(s.gl.buffer_bytes),
                     mib(s.gl.texture_bytes), mib(s.rss), mib(s.streamed), s.failed_chunks, s.resident_chunks,
                     static_cast<unsigned long long>(s.failed_events));
}

constexpr const char* kCsvHeader =
    "lap,frame,lap_end,faults_active,gl_objects,gl_buffers,gl_textures,gl_vao_fbo,gl_programs_shaders,"
    "gl_samplers_queries,gl_buffer_mib,gl_texture_mib,rss_mib,streamed_mib,failed_chunks,resident_chunks,"
    "failed_events\n";

// soak_memory.png (RSS, GL bytes and streamed bytes along the frames, lap ends marked, fault
// windows shaded) and soak_objects.png (GL objects). Returns why there are none, or "".
std::string write_plots(const std::filesystem::path& out, const std::vector<Sample>& samples) {
    const std::string terminal = engine::gnuplot_png_terminal();
    if (terminal.empty()) return "gnuplot not found; install gnuplot-nox (scripts/setup does) for the soak plots";
    std::string shading;
    int object = 1;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        if (!samples[i].faults_active || (i > 0 && samples[i - 1].faults_active)) continue;
        std::size_t j = i;
        while (j + 1 < samples.size() && samples[j + 1].faults_active) ++j;
        shading += formatted("set object %d rect from %llu, graph 0 to %llu, graph 1 behind fc rgb '#fde0dc' "
                             "fs solid 1.0 noborder\n",
                             object++, static_cast<unsigned long long>(samples[i].frame),
                             static_cast<unsigned long long>(j + 1 < samples.size() ? samples[j + 1].frame
                                                                                    : samples[j].frame));
    }
    std::ostringstream gp;
    gp << "set datafile separator ','\nset key below\nset grid\nset xlabel 'frame'\n" << shading
       << "set terminal " << terminal << " size 1000,420\nset output 'soak_memory.png'\n"
       << "set title 'Soak: memory at every sample (red: chunk files damaged; points: lap ends)'\n"
       << "set ylabel 'MiB'\n"
       << "plot 'soak.csv' using 2:13 skip 1 with lines lw 2 title 'process RSS', "
          "'' using 2:($11+$12) skip 1 with lines lw 2 title 'GL buffers + textures', "
          "'' using 2:14 skip 1 with lines lw 2 title 'streamed (resident)', "
          "'' using 2:($3 > 0 ? $13 : 1/0) skip 1 with points pt 7 ps 1.2 lc rgb 'black' title 'lap end'\n"
       << "set output 'soak_objects.png'\nset title 'Soak: GL objects the driver holds, and failed chunks'\n"
       << "set ylabel 'objects'\nset y2label 'failed chunks'\nset y2tics\nset ytics nomirror\n"
       << "plot 'soak.csv' using 2:5 skip 1 with lines lw 2 title 'GL objects', "
          "'' using 2:6 skip 1 with lines title 'buffers', '' using 2:7 skip 1 with lines title 'textures', "
          "'' using 2:15 skip 1 axes x1y2 with steps lw 2 title 'failed chunks'\n";
    engine::write_text_file_atomic(out / "soak_plots.gp", gp.str());
    engine::run_gnuplot(out, "soak_plots.gp", "soak_plots.log");
    return "";
}

bool within(std::uint64_t value, std::uint64_t reference, std::uint64_t slack, double share) {
    return static_cast<double>(value) <=
           static_cast<double>(reference) + static_cast<double>(slack) + share * static_cast<double>(reference);
}

std::string check(bool ok, const std::string& text) {
    return std::string(ok ? "PASS " : "FAIL ") + text;
}

}  // namespace

void validate(const SoakOptions& o) {
    if (o.world.empty()) engine::fail("sample_game: --world is required (a folder holding world.json)");
    if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
        engine::fail("sample_game: --width and --height must be 16..16384");
    if (o.frames_per_lap < 20)
        engine::fail("sample_game: --frames (per soak lap) must be at least 20, got " + std::to_string(o.frames_per_lap));
    if (o.laps < (o.faults ? 3 : 2))
        engine::fail(std::string("sample_game: --laps must be at least ") + (o.faults ? "3 with faults" : "2") +
                     " (the first lap is the reference), got " + std::to_string(o.laps));
    if (o.sample_every < 1) engine::fail("sample_game: the soak's sample interval must be at least 1 frame");
    if (o.faults && o.settings.retry_failed_after_frames <= 0)
        engine::fail("sample_game: a soak with faults needs retries (retry_failed_after_frames > 0)");
    if (o.faults && o.settings.retry_failed_after_frames > kMaxRetryFrames)
        engine::fail("sample_game: the soak's retry interval (" + std::to_string(o.settings.retry_failed_after_frames) +
                     " frames) must be at most " + std::to_string(kMaxRetryFrames) +
                     " frames, so that a lap end can wait for it");
    validate(o.settings);
    require_world_folder(o.world);
}

SoakOutcome run_soak(const SoakOptions& o, std::FILE* progress) {
    validate(o);
    const auto start = Clock::now();
    std::filesystem::create_directories(o.out);
    for (const char* name : {"soak.csv", "soak_summary.txt", "soak_memory.png", "soak_objects.png", "soak_plots.gp",
                             "soak_plots.log", "lap_end_first.png", "lap_end_last.png"})
        std::filesystem::remove(o.out / name);
    std::filesystem::path world_folder = o.world;
    if (o.faults) {
        world_folder = o.out / "world_copy";
        make_linked_world_copy(o.world, world_folder);
    }

    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    GameWorld world(engine, world_folder, o.settings);
    const std::vector<PathPose> poses = sample_world_path(world.terrain(), o.frames_per_lap);
    world.warm_up(o.width, o.height);
    const auto& chunks = world.manifest().chunks;

    // The replacement's donor: the chunk farthest from the path's start.
    std::vector<std::size_t> order(chunks.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const glm::vec3 home = poses.front().eye;
    const auto distance = [&](std::size_t i) {
        const glm::vec3 centre = 0.5f * (chunks[i].bounds_min + chunks[i].bounds_max);
        return glm::length(glm::vec2(centre.x - home.x, centre.z - home.z));
    };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return distance(a) < distance(b); });
    if (o.faults && chunks.size() < 5)
        engine::fail("sample_game: the soak's faults need a world of at least 5 chunks, " + o.world.string() + " has " +
                     std::to_string(chunks.size()));
    std::optional<ChunkFaults> faults;
    if (o.faults) faults.emplace(world_folder, world.manifest());
    const FaultKind kinds[] = {FaultKind::removed, FaultKind::truncated, FaultKind::replaced, FaultKind::corrupted};
    constexpr std::size_t kVictims = std::size(kinds);
    // The victims of a lap: of the chunks that lost levels since the last lap end (so the camera's
    // return reads them again), the four nearest the start; the nearest chunks when fewer lost any.
    std::map<std::string, FaultKind> victims;
    std::vector<int> finest_at_lap_end(chunks.size(), 0);
    const auto choose_victims = [&]() {
        std::vector<std::size_t> lost, rest;
        for (const std::size_t i : order) {
            if (i == order.back()) continue;  // the donor
            const bool lost_levels = world.streamer().chunk_status(i).finest_resident_level > finest_at_lap_end[i] ||
                                     (finest_at_lap_end[i] > 0 && world.streamer().chunk_status(i).finest_resident_level == 0);
            (lost_levels ? lost : rest).push_back(i);
        }
        lost.insert(lost.end(), rest.begin(), rest.end());
        lost.resize(kVictims);
        return lost;
    };

    SoakOutcome outcome;
    std::vector<Sample> samples;
    std::uint64_t failed_events = 0;
    engine::RenderTarget target(o.width, o.height);
    std::optional<splat_lod::eval::FloatImage> first_image;
    std::uint64_t frame = 0;
    const int fault_begin = static_cast<int>(kFaultStart * o.frames_per_lap);

    const auto take_sample = [&](int lap, bool lap_end) {
        Sample s;
        s.lap = lap;
        s.frame = frame;
        s.lap_end = lap_end;
        s.faults_active = faults && !faults->active().empty();
        s.gl = engine::gl::take_gl_census();
        s.rss = engine::process_memory().resident_bytes;
        s.streamed = world.streamer().resident_bytes();
        const ChunkCensus census = world.census();
        s.failed_chunks = census.failed;
        s.resident_chunks = census.resident;
        s.failed_events = failed_events;
        samples.push_back(s);
        return s;
    };
    const auto count_failures = [&]() {
        for (const auto& event : world.streamer().last_events()) {
            if (event.event != plugin_msgs::StreamEventType::failed) continue;
            ++failed_events;
            const auto it = victims.find(event.chunk_id);
            if (it == victims.end()) {
                ++outcome.failures_undamaged;
                if (progress) std::fprintf(progress, "sample_game: soak: undamaged chunk failed: %s %s\n",
                                           event.chunk_id.c_str(), event.message.c_str());
            } else if (it->second == FaultKind::removed) {
                ++outcome.failures_removed;
            } else if (it->second == FaultKind::truncated) {
                ++outcome.failures_truncated;
            } else if (it->second == FaultKind::replaced) {
                ++outcome.failures_replaced;
            } else {
                ++outcome.failures_corrupted;
            }
        }
    };

    for (int lap = 1; lap <= o.laps; ++lap) {
        const bool faulted_lap = faults && lap > 1 && lap < o.laps;
        const auto lap_start = Clock::now();
        for (int i = 0; i < o.frames_per_lap; ++i, ++frame) {
            if (faulted_lap && i == fault_begin) {
                const std::vector<std::size_t> chosen = choose_victims();
                victims.clear();
                for (std::size_t k = 0; k < kVictims; ++k) {
                    faults->apply(chosen[k], kinds[k], order.back());
                    victims[chunks[chosen[k]].id] = kinds[k];
                }
            }
            const engine::CameraView camera = world.camera(poses[static_cast<std::size_t>(i)], o.width, o.height);
            world.update_streaming(camera, frame);
            count_failures();
            engine.renderer().render(world.scene(), camera, target);
            if (i % o.sample_every == 0) take_sample(lap, false);
        }
        if (faults) faults->restore_all();
        if (o.after_lap) o.after_lap(lap);
        // Settle at the last pose: the lap's end state, comparable from lap to lap.
        const engine::CameraView camera = world.camera(poses.back(), o.width, o.height);
        std::uint32_t settle = 0;
        for (int quiet = 0; settle < kMaxSettleUpdates && quiet < 3; ++settle, ++frame) {
            world.update_streaming(camera, frame);
            world.streamer().wait_idle();
            count_failures();
            engine.renderer().render(world.scene(), camera, target);
            const ChunkCensus census = world.census();
            const bool idle = world.streamer().stats().uploaded_bytes_last_update == 0 && census.requested == 0 &&
                              census.loaded == 0 && census.partial == 0 && census.failed == 0;
            quiet = idle ? quiet + 1 : 0;
        }
        splat_lod::render_complete(engine, world.scene(), camera, target);
        engine.renderer().timers().wait_all();
        world.pass().wait_for_statistics(engine.bus());
        const engine::Image image = target.read_color();
        const auto pixels = splat_lod::eval::to_float(image);
        if (!first_image) {
            first_image = pixels;
            engine::write_png(o.out / "lap_end_first.png", image);
        }
        if (lap == o.laps) engine::write_png(o.out / "lap_end_last.png", image);
        const Sample s = take_sample(lap, true);
        for (std::size_t i = 0; i < chunks.size(); ++i)
            finest_at_lap_end[i] = world.streamer().chunk_status(i).finest_resident_level;
        SoakLapEnd end;
        end.lap = lap;
        end.frame = frame;
        end.gl_objects = s.gl.objects();
        end.gl_bytes = s.gl.buffer_bytes + s.gl.texture_bytes;
        end.rss_bytes = s.rss;
        end.streamed_bytes = s.streamed;
        end.failed_chunks = s.failed_chunks;
        end.settle_updates = settle;
        end.psnr_vs_first = splat_lod::eval::psnr(pixels, *first_image);
        end.gl_census = s.gl.describe();
        outcome.lap_ends.push_back(end);
        if (progress) {
            std::fprintf(progress,
                         "sample_game: soak lap %d/%d (%.0f s%s): RSS %.1f MiB, GL %u objects %.2f MiB, streamed "
                         "%.1f MiB, %u failed chunks, %llu failures so far, settled in %u updates, %.1f dB vs lap 1\n",
                         lap, o.laps, seconds_since(lap_start), faulted_lap ? ", chunk files damaged" : "",
                         mib(end.rss_bytes), end.gl_objects, mib(end.gl_bytes), mib(end.streamed_bytes),
                         end.failed_chunks, static_cast<unsigned long long>(failed_events), settle, end.psnr_vs_first);
            std::fflush(progress);
        }
    }

    std::string csv = kCsvHeader;
    for (const Sample& s : samples) csv += csv_row(s);
    engine::write_text_file_atomic(o.out / "soak.csv", csv);
    try {
        outcome.plot_problem = write_plots(o.out, samples);
    } catch (const engine::Error& e) {
        outcome.plot_problem = e.what();
    }

    // The checks.
    const auto& ends = outcome.lap_ends;
    const SoakLapEnd& first = ends.front();
    const SoakLapEnd& reference = ends.size() >= 3 ? ends[1] : ends.front();
    const SoakLapEnd& last = ends.back();
    const Sample* first_sample = nullptr;
    bool same_objects = true;
    int first_different = 0;
    for (const Sample& s : samples) {
        if (!s.lap_end) continue;
        if (first_sample == nullptr) first_sample = &s;
        if (!s.gl.same_objects(first_sample->gl) && same_objects) {
            same_objects = false;
            first_different = s.lap;
        }
    }
    auto& c = outcome.checks;
    c.push_back(check(same_objects, same_objects
                                         ? formatted("GL objects: %u at every lap end (%s)", first.gl_objects,
                                                     first.gl_census.c_str())
                                         : formatted("GL objects: lap %d ends with %s, lap 1 with %s", first_different,
                                                     ends[static_cast<std::size_t>(first_different - 1)].gl_census.c_str(),
                                                     first.gl_census.c_str())));
    c.push_back(check(within(last.gl_bytes, reference.gl_bytes, kGlBytesSlack, kGlBytesShare),
                      formatted("GL memory: %.2f MiB at the last lap end, %.2f MiB at lap %d's (limit +1 MiB)",
                                mib(last.gl_bytes), mib(reference.gl_bytes), reference.lap)));
    c.push_back(check(within(last.rss_bytes, reference.rss_bytes, kRssSlack, kRssShare),
                      formatted("CPU memory: RSS %.1f MiB at the last lap end, %.1f MiB at lap %d's (limit +16 MiB + "
                                "2 %%)",
                                mib(last.rss_bytes), mib(reference.rss_bytes), reference.lap)));
    const double streamed_change =
        reference.streamed_bytes > 0
            ? std::abs(static_cast<double>(last.streamed_bytes) - static_cast<double>(reference.streamed_bytes)) /
                  static_cast<double>(reference.streamed_bytes)
            : (last.streamed_bytes > 0 ? 1.0 : 0.0);
    c.push_back(check(last.failed_chunks == 0 && streamed_change <= kStreamedShare,
                      formatted("streaming recovers: %u failed chunks at the last lap end, streamed %.1f MiB against "
                                "%.1f MiB at lap %d's",
                                last.failed_chunks, mib(last.streamed_bytes), mib(reference.streamed_bytes),
                                reference.lap)));
    if (o.faults)
        c.push_back(check(outcome.failures_removed > 0 && outcome.failures_truncated > 0 &&
                              outcome.failures_replaced > 0 && outcome.failures_corrupted > 0 &&
                              outcome.failures_undamaged == 0,
                          formatted("faults noticed: failures of removed %llu, truncated %llu, replaced %llu, "
                                    "corrupted %llu chunk files; of undamaged chunks %llu",
                                    static_cast<unsigned long long>(outcome.failures_removed),
                                    static_cast<unsigned long long>(outcome.failures_truncated),
                                    static_cast<unsigned long long>(outcome.failures_replaced),
                                    static_cast<unsigned long long>(outcome.failures_corrupted),
                                    static_cast<unsigned long long>(outcome.failures_undamaged))));
    double worst_psnr = std::numeric_limits<double>::infinity();
    for (const auto& e : ends) worst_psnr = std::min(worst_psnr, e.psnr_vs_first);
    c.push_back(check(worst_psnr >= kMinPsnr,
                      formatted("no lasting damage on screen: lap-end frames within %.1f dB PSNR of lap 1's (limit "
                                "%.0f dB)",
                                worst_psnr, kMinPsnr)));
    outcome.passed = std::all_of(c.begin(), c.end(), [](const std::string& line) { return line.rfind("PASS", 0) == 0; });

    std::string text = formatted("sample_game soak: %s, %d laps of %d frames at %dx%d, faults %s, %.0f s\n",
                                 o.world.string().c_str(), o.laps, o.frames_per_lap, o.width, o.height,
                                 o.faults ? "on (removed, truncated, replaced, corrupted chunk files)" : "off",
                                 seconds_since(start));
    text += "lap  frame  GL objects  GL MiB  RSS MiB  streamed MiB  failed  settle  PSNR vs lap 1\n";
    for (const auto& e : ends)
        text += formatted("%3d %6llu %11u %7.2f %8.1f %13.1f %7u %7u %14.1f\n", e.lap,
                          static_cast<unsigned long long>(e.frame), e.gl_objects, mib(e.gl_bytes), mib(e.rss_bytes),
                          mib(e.streamed_bytes), e.failed_chunks, e.settle_updates, e.psnr_vs_first);
    for (const auto& line : c) text += line + "\n";
    text += outcome.passed ? "soak: PASSED\n" : "soak: FAILED\n";
    if (!outcome.plot_problem.empty()) text += "NO PLOTS: " + outcome.plot_problem + "\n";
    outcome.summary_text = text;
    engine::write_text_file_atomic(o.out / "soak_summary.txt", text);
    return outcome;
}

}  // namespace sample_game
