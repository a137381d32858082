#include "sample_game/harness/soak_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/core/gnuplot.h"
#include "engine/core/process_memory.h"
#include "engine/engine.h"
#include "engine/gl/gl_census.h"
#include "engine/render/render_target.h"
#include "formatted.h"
#include "sample_game/game_world.h"
#include "sample_game/harness/chunk_faults.h"
#include "sample_game/world_path.h"
#include "splat_lod/eval/image_metrics.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"

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
        shading += formatted(
            "set object %d rect from %llu, graph 0 to %llu, graph 1 behind fc rgb '#fde0dc' "
            "fs solid 1.0 noborder\n",
            object++, static_cast<unsigned long long>(samples[i].frame),
            static_cast<unsigned long long>(j + 1 < samples.size() ? samples[j + 1].frame : samples[j].frame));
    }
    std::ostringstream gp;
    gp << "set datafile separator ','\nset key below\nset grid\nset xlabel 'frame'\n"
       << shading << "set terminal " << terminal << " size 1000,420\nset output 'soak_memory.png'\n"
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

// What a faulted lap does to its victims, the nearest chunk first.
constexpr FaultKind kFaultKinds[] = {FaultKind::removed, FaultKind::truncated, FaultKind::replaced,
                                     FaultKind::corrupted};
constexpr std::size_t kVictims = std::size(kFaultKinds);

// Clears an earlier run's outputs, so that none of them passes for this run's, and returns the folder to
// stream from: with faults, a linked copy of the world, since the faults damage its files.
std::filesystem::path prepare_outputs(const SoakOptions& o) {
    std::filesystem::create_directories(o.out);
    for (const char* name : {"soak.csv", "soak_summary.txt", "soak_memory.png", "soak_objects.png", "soak_plots.gp",
                             "soak_plots.log", "lap_end_first.png", "lap_end_last.png"})
        std::filesystem::remove(o.out / name);
    std::filesystem::path world_folder = o.world;
    if (o.faults) {
        world_folder = o.out / "world_copy";
        make_linked_world_copy(o.world, world_folder);
    }
    return world_folder;
}

// The chunks nearest the path's start first; the last, the farthest, is the replacement's donor.
std::vector<std::size_t> chunks_by_distance(const std::vector<splat_lod::world::ChunkEntry>& chunks,
                                            const glm::vec3 home) {
    std::vector<std::size_t> order(chunks.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const auto distance = [&](std::size_t i) {
        const glm::vec3 centre = 0.5f * (chunks[i].bounds_min + chunks[i].bounds_max);
        return glm::length(glm::vec2(centre.x - home.x, centre.z - home.z));
    };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return distance(a) < distance(b); });
    return order;
}

// The laps of one soak and what they leave behind: the samples, the lap ends and the failures seen.
// It holds the render target, so it must go before the engine, the world and the faults it refers to.
class SoakWalk {
public:
    SoakWalk(const SoakOptions& o, std::FILE* progress, engine::Engine& engine, GameWorld& world,
             const std::vector<PathPose>& poses, const std::vector<std::size_t>& order,
             std::optional<ChunkFaults>& faults)
        : o_(o),
          progress_(progress),
          engine_(engine),
          world_(world),
          poses_(poses),
          chunks_(world.manifest().chunks),
          order_(order),
          faults_(faults),
          finest_at_lap_end_(chunks_.size(), 0),
          target_(o.width, o.height),
          fault_begin_(static_cast<int>(kFaultStart * o.frames_per_lap)) {}

    void run_lap(int lap);
    SoakOutcome& outcome() { return outcome_; }
    const std::vector<Sample>& samples() const { return samples_; }

private:
    std::vector<std::size_t> choose_victims();
    void damage_victims();
    Sample take_sample(int lap, bool lap_end);
    void count_failures();
    void walk(int lap, bool faulted_lap);
    std::uint32_t settle(const engine::CameraView& camera);
    const SoakLapEnd& measure_lap_end(int lap, const engine::CameraView& camera, std::uint32_t settle_updates);
    void report_lap(const SoakLapEnd& end, bool faulted_lap, Clock::time_point lap_start) const;

    const SoakOptions& o_;
    std::FILE* progress_;
    engine::Engine& engine_;
    GameWorld& world_;
    const std::vector<PathPose>& poses_;
    const std::vector<splat_lod::world::ChunkEntry>& chunks_;
    const std::vector<std::size_t>& order_;
    std::optional<ChunkFaults>& faults_;
    std::map<std::string, FaultKind> victims_;
    std::vector<int> finest_at_lap_end_;
    SoakOutcome outcome_;
    std::vector<Sample> samples_;
    std::uint64_t failed_events_ = 0;
    engine::RenderTarget target_;
    std::optional<splat_lod::eval::FloatImage> first_image_;
    std::uint64_t frame_ = 0;
    const int fault_begin_;
};

// The victims of a lap: of the chunks that lost levels since the last lap end (so the camera's
// return reads them again), the four nearest the start; the nearest chunks when fewer lost any.
std::vector<std::size_t> SoakWalk::choose_victims() {
    std::vector<std::size_t> lost, rest;
    for (const std::size_t i : order_) {
        if (i == order_.back()) continue;  // the donor
        const bool lost_levels =
            world_.streamer().chunk_status(i).finest_resident_level > finest_at_lap_end_[i] ||
            (finest_at_lap_end_[i] > 0 && world_.streamer().chunk_status(i).finest_resident_level == 0);
        (lost_levels ? lost : rest).push_back(i);
    }
    lost.insert(lost.end(), rest.begin(), rest.end());
    lost.resize(kVictims);
    return lost;
}

void SoakWalk::damage_victims() {
    const std::vector<std::size_t> chosen = choose_victims();
    victims_.clear();
    for (std::size_t k = 0; k < kVictims; ++k) {
        faults_->apply(chosen[k], kFaultKinds[k], order_.back());
        victims_[chunks_[chosen[k]].id] = kFaultKinds[k];
    }
}

Sample SoakWalk::take_sample(int lap, bool lap_end) {
    Sample s;
    s.lap = lap;
    s.frame = frame_;
    s.lap_end = lap_end;
    s.faults_active = faults_ && !faults_->active().empty();
    s.gl = engine::gl::take_gl_census();
    s.rss = engine::process_memory().resident_bytes;
    s.streamed = world_.streamer().resident_bytes();
    const ChunkCensus census = world_.census();
    s.failed_chunks = census.failed;
    s.resident_chunks = census.resident;
    s.failed_events = failed_events_;
    samples_.push_back(s);
    return s;
}

// Sorts the streamer's failures of the last update by the fault on their chunk.
void SoakWalk::count_failures() {
    for (const auto& event : world_.streamer().last_events()) {
        if (event.event != plugin_msgs::StreamEventType::failed) continue;
        ++failed_events_;
        const auto it = victims_.find(event.chunk_id);
        if (it == victims_.end()) {
            ++outcome_.failures_undamaged;
            if (progress_)
                std::fprintf(progress_, "sample_game_harness: soak: undamaged chunk failed: %s %s\n",
                             event.chunk_id.c_str(), event.message.c_str());
        } else if (it->second == FaultKind::removed) {
            ++outcome_.failures_removed;
        } else if (it->second == FaultKind::truncated) {
            ++outcome_.failures_truncated;
        } else if (it->second == FaultKind::replaced) {
            ++outcome_.failures_replaced;
        } else {
            ++outcome_.failures_corrupted;
        }
    }
}

void SoakWalk::run_lap(int lap) {
    const bool faulted_lap = faults_ && lap > 1 && lap < o_.laps;
    const auto lap_start = Clock::now();
    walk(lap, faulted_lap);
    if (faults_) faults_->restore_all();
    if (o_.after_lap) o_.after_lap(lap);
    // Settle at the last pose: the lap's end state, comparable from lap to lap.
    const engine::CameraView camera = world_.camera(poses_.back(), o_.width, o_.height);
    const std::uint32_t settle_updates = settle(camera);
    report_lap(measure_lap_end(lap, camera, settle_updates), faulted_lap, lap_start);
}

// The lap's walk along the path, damaging the victims' files from kFaultStart of a faulted lap on.
void SoakWalk::walk(int lap, bool faulted_lap) {
    for (int i = 0; i < o_.frames_per_lap; ++i, ++frame_) {
        if (faulted_lap && i == fault_begin_) damage_victims();
        const engine::CameraView camera = world_.camera(poses_[static_cast<std::size_t>(i)], o_.width, o_.height);
        world_.update_streaming(camera, frame_, pose_velocity(poses_, static_cast<std::size_t>(i)));
        count_failures();
        engine_.renderer().render(world_.scene(), camera, target_);
        if (i % o_.sample_every == 0) take_sample(lap, false);
    }
}

// Updates until three updates in a row read, upload and fail nothing (or kMaxSettleUpdates pass);
// returns how many it took.
std::uint32_t SoakWalk::settle(const engine::CameraView& camera) {
    std::uint32_t settle_updates = 0;
    for (int quiet = 0; settle_updates < kMaxSettleUpdates && quiet < 3; ++settle_updates, ++frame_) {
        world_.update_streaming(camera, frame_);
        world_.streamer().wait_idle();
        count_failures();
        engine_.renderer().render(world_.scene(), camera, target_);
        const ChunkCensus census = world_.census();
        const bool idle = world_.streamer().stats().uploaded_bytes_last_update == 0 && census.requested == 0 &&
                          census.loaded == 0 && census.partial == 0 && census.failed == 0;
        quiet = idle ? quiet + 1 : 0;
    }
    return settle_updates;
}

// Draws the settled frame in full, keeps the first and last lap ends' images and records the lap end.
const SoakLapEnd& SoakWalk::measure_lap_end(int lap, const engine::CameraView& camera, std::uint32_t settle_updates) {
    splat_lod::render_complete(engine_, world_.scene(), camera, target_);
    engine_.renderer().timers().wait_all();
    world_.pass().wait_for_statistics(engine_.bus());
    const engine::Image image = target_.read_color();
    const auto pixels = splat_lod::eval::to_float(image);
    if (!first_image_) {
        first_image_ = pixels;
        engine::write_png(o_.out / "lap_end_first.png", image);
    }
    if (lap == o_.laps) engine::write_png(o_.out / "lap_end_last.png", image);
    const Sample s = take_sample(lap, true);
    for (std::size_t i = 0; i < chunks_.size(); ++i)
        finest_at_lap_end_[i] = world_.streamer().chunk_status(i).finest_resident_level;
    SoakLapEnd end;
    end.lap = lap;
    end.frame = frame_;
    end.gl_objects = s.gl.objects();
    end.gl_bytes = s.gl.buffer_bytes + s.gl.texture_bytes;
    end.rss_bytes = s.rss;
    end.streamed_bytes = s.streamed;
    end.failed_chunks = s.failed_chunks;
    end.settle_updates = settle_updates;
    end.psnr_vs_first = splat_lod::eval::psnr(pixels, *first_image_);
    end.gl_census = s.gl.describe();
    outcome_.lap_ends.push_back(end);
    return outcome_.lap_ends.back();
}

void SoakWalk::report_lap(const SoakLapEnd& end, bool faulted_lap, Clock::time_point lap_start) const {
    if (!progress_) return;
    std::fprintf(progress_,
                 "sample_game_harness: soak lap %d/%d (%.0f s%s): RSS %.1f MiB, GL %u objects %.2f MiB, streamed "
                 "%.1f MiB, %u failed chunks, %llu failures so far, settled in %u updates, %.1f dB vs lap 1\n",
                 end.lap, o_.laps, seconds_since(lap_start), faulted_lap ? ", chunk files damaged" : "",
                 mib(end.rss_bytes), end.gl_objects, mib(end.gl_bytes), mib(end.streamed_bytes), end.failed_chunks,
                 static_cast<unsigned long long>(failed_events_), end.settle_updates, end.psnr_vs_first);
    std::fflush(progress_);
}

// soak.csv and the plots made from it; a plot that cannot be made is a note, not a failure.
void write_samples(const std::filesystem::path& out, const std::vector<Sample>& samples, SoakOutcome& outcome) {
    std::string csv = kCsvHeader;
    for (const Sample& s : samples) csv += csv_row(s);
    engine::write_text_file_atomic(out / "soak.csv", csv);
    try {
        outcome.plot_problem = write_plots(out, samples);
    } catch (const engine::Error& e) {
        outcome.plot_problem = e.what();
    }
}

// Check 1: every lap end holds the objects of the first, else the first lap end that does not.
std::string gl_objects_check(const std::vector<Sample>& samples, const std::vector<SoakLapEnd>& ends) {
    const SoakLapEnd& first = ends.front();
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
    return check(same_objects,
                 same_objects
                     ? formatted("GL objects: %u at every lap end (%s)", first.gl_objects, first.gl_census.c_str())
                     : formatted("GL objects: lap %d ends with %s, lap 1 with %s", first_different,
                                 ends[static_cast<std::size_t>(first_different - 1)].gl_census.c_str(),
                                 first.gl_census.c_str()));
}

// Check 5: every kind of damage made a chunk fail, and nothing else did.
std::string faults_check(const SoakOutcome& outcome) {
    return check(outcome.failures_removed > 0 && outcome.failures_truncated > 0 && outcome.failures_replaced > 0 &&
                     outcome.failures_corrupted > 0 && outcome.failures_undamaged == 0,
                 formatted("faults noticed: failures of removed %llu, truncated %llu, replaced %llu, "
                           "corrupted %llu chunk files; of undamaged chunks %llu",
                           static_cast<unsigned long long>(outcome.failures_removed),
                           static_cast<unsigned long long>(outcome.failures_truncated),
                           static_cast<unsigned long long>(outcome.failures_replaced),
                           static_cast<unsigned long long>(outcome.failures_corrupted),
                           static_cast<unsigned long long>(outcome.failures_undamaged)));
}

// The checks of soak_run.h, in its order, and whether all passed.
void add_checks(const SoakOptions& o, const std::vector<Sample>& samples, SoakOutcome& outcome) {
    const auto& ends = outcome.lap_ends;
    const SoakLapEnd& reference = ends.size() >= 3 ? ends[1] : ends.front();
    const SoakLapEnd& last = ends.back();
    auto& c = outcome.checks;
    c.push_back(gl_objects_check(samples, ends));
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
    c.push_back(
        check(last.failed_chunks == 0 && streamed_change <= kStreamedShare,
              formatted("streaming recovers: %u failed chunks at the last lap end, streamed %.1f MiB against "
                        "%.1f MiB at lap %d's",
                        last.failed_chunks, mib(last.streamed_bytes), mib(reference.streamed_bytes), reference.lap)));
    if (o.faults) c.push_back(faults_check(outcome));
    double worst_psnr = std::numeric_limits<double>::infinity();
    for (const auto& e : ends) worst_psnr = std::min(worst_psnr, e.psnr_vs_first);
    c.push_back(check(worst_psnr >= kMinPsnr,
                      formatted("no lasting damage on screen: lap-end frames within %.1f dB PSNR of lap 1's (limit "
                                "%.0f dB)",
                                worst_psnr, kMinPsnr)));
    outcome.passed =
        std::all_of(c.begin(), c.end(), [](const std::string& line) { return line.rfind("PASS", 0) == 0; });
}

std::string summary_text(const SoakOptions& o, Clock::time_point start, const SoakOutcome& outcome) {
    std::string text =
        formatted("sample_game soak: %s, %d laps of %d frames at %dx%d, faults %s, %.0f s\n", o.world.string().c_str(),
                  o.laps, o.frames_per_lap, o.width, o.height,
                  o.faults ? "on (removed, truncated, replaced, corrupted chunk files)" : "off", seconds_since(start));
    text += "lap  frame  GL objects  GL MiB  RSS MiB  streamed MiB  failed  settle  PSNR vs lap 1\n";
    for (const auto& e : outcome.lap_ends)
        text += formatted("%3d %6llu %11u %7.2f %8.1f %13.1f %7u %7u %14.1f\n", e.lap,
                          static_cast<unsigned long long>(e.frame), e.gl_objects, mib(e.gl_bytes), mib(e.rss_bytes),
                          mib(e.streamed_bytes), e.failed_chunks, e.settle_updates, e.psnr_vs_first);
    for (const auto& line : outcome.checks) text += line + "\n";
    text += outcome.passed ? "soak: PASSED\n" : "soak: FAILED\n";
    if (!outcome.plot_problem.empty()) text += "NO PLOTS: " + outcome.plot_problem + "\n";
    return text;
}

}  // namespace

void validate(const SoakOptions& o) {
    if (o.world.empty()) engine::fail("sample_game_harness: --world is required (a folder holding world.json)");
    if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
        engine::fail("sample_game_harness: --width and --height must be 16..16384");
    if (o.frames_per_lap < 20)
        engine::fail("sample_game_harness: --frames (per soak lap) must be at least 20, got " +
                     std::to_string(o.frames_per_lap));
    if (o.laps < (o.faults ? 3 : 2))
        engine::fail(std::string("sample_game_harness: --laps must be at least ") + (o.faults ? "3 with faults" : "2") +
                     " (the first lap is the reference), got " + std::to_string(o.laps));
    if (o.sample_every < 1) engine::fail("sample_game_harness: the soak's sample interval must be at least 1 frame");
    if (o.faults && o.settings.retry_failed_after_frames <= 0)
        engine::fail("sample_game_harness: a soak with faults needs retries (retry_failed_after_frames > 0)");
    if (o.faults && o.settings.retry_failed_after_frames > kMaxRetryFrames)
        engine::fail("sample_game_harness: the soak's retry interval (" +
                     std::to_string(o.settings.retry_failed_after_frames) + " frames) must be at most " +
                     std::to_string(kMaxRetryFrames) + " frames, so that a lap end can wait for it");
    validate(o.settings);
    require_world_folder(o.world);
}

SoakOutcome run_soak(const SoakOptions& o, std::FILE* progress) {
    validate(o);
    const auto start = Clock::now();
    const std::filesystem::path world_folder = prepare_outputs(o);

    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    GameWorld world(engine, world_folder, o.settings);
    const std::vector<PathPose> poses = world.path(o.frames_per_lap);
    world.warm_up(o.width, o.height);
    const auto& chunks = world.manifest().chunks;
    const std::vector<std::size_t> order = chunks_by_distance(chunks, poses.front().eye);
    if (o.faults && chunks.size() < 5)
        engine::fail("sample_game_harness: the soak's faults need a world of at least 5 chunks, " + o.world.string() +
                     " has " + std::to_string(chunks.size()));
    std::optional<ChunkFaults> faults;
    if (o.faults) faults.emplace(world_folder, world.manifest());

    SoakWalk walk(o, progress, engine, world, poses, order, faults);
    for (int lap = 1; lap <= o.laps; ++lap) walk.run_lap(lap);

    SoakOutcome& outcome = walk.outcome();
    write_samples(o.out, walk.samples(), outcome);
    add_checks(o, walk.samples(), outcome);
    outcome.summary_text = summary_text(o, start, outcome);
    engine::write_text_file_atomic(o.out / "soak_summary.txt", outcome.summary_text);
    return std::move(outcome);
}

}  // namespace sample_game
