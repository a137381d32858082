#include "sample_game/harness/profile_summary.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include "formatted.h"
#include "sample_game/game_settings.h"

namespace sample_game {
namespace {

double mib(std::uint64_t bytes) {
    return static_cast<double>(bytes) / static_cast<double>(kMiB);
}

void segment_times(const std::vector<FrameRecord>& lod, const std::vector<FrameRecord>& baseline, ProfileSummary& s) {
    std::map<int, double> lod_ms;
    for (const auto& r : lod) lod_ms[r.frame] = r.frame_ms;
    for (std::size_t k = 0; k < kSegmentCount; ++k) {
        std::vector<double> times, base, lod_same;
        for (const auto& r : lod)
            if (static_cast<std::size_t>(r.segment) == k) times.push_back(r.frame_ms);
        for (const auto& r : baseline)
            if (static_cast<std::size_t>(r.segment) == k && lod_ms.count(r.frame)) {
                base.push_back(r.frame_ms);
                lod_same.push_back(lod_ms[r.frame]);
            }
        SegmentTimes& t = s.segments[k];
        t.frames = static_cast<int>(times.size());
        if (!times.empty()) {
            double sum = 0.0;
            for (double v : times) sum += v;
            t.mean_ms = sum / static_cast<double>(times.size());
            t.max_ms = *std::max_element(times.begin(), times.end());
        }
        t.median_ms = median_of(times);
        t.baseline_frames = static_cast<int>(base.size());
        t.baseline_median_ms = median_of(base);
        t.lod_median_same_ms = median_of(lod_same);
    }
}

void budget_checks(const std::vector<FrameRecord>& lod, ProfileSummary& s) {
    for (const auto& r : lod) {
        s.peak_resident_bytes = std::max(s.peak_resident_bytes, r.resident_bytes);
        if (r.gpu_total_bytes > s.peak_gpu_total_bytes) {
            s.peak_gpu_total_bytes = r.gpu_total_bytes;
            s.peak_scene_bytes = r.gpu_scene_bytes;
            s.peak_frame_bytes = r.gpu_frame_bytes;
        }
        s.max_upload_bytes = std::max(s.max_upload_bytes, r.stream_upload_bytes);
        s.max_gpu_upload_bytes = std::max(s.max_gpu_upload_bytes, r.gpu_upload_bytes);
        s.total_upload_bytes += r.stream_upload_bytes;
        s.frames_over_memory += r.resident_bytes > s.memory_budget_bytes ? 1 : 0;
        s.frames_over_upload += r.stream_upload_bytes > s.upload_budget_bytes ? 1 : 0;
        s.frames_pages_differ += r.gpu_page_bytes != r.resident_bytes + r.props_gpu_bytes ? 1 : 0;
        s.failures = std::max(s.failures, r.failures_total);
        s.reselected_frames += r.selection_runs > 1 ? 1 : 0;
        s.striped_frames += r.strips > 1 ? 1 : 0;
        s.most_strips = std::max(s.most_strips, r.strips);
    }
    s.memory.measured = !lod.empty();
    s.memory.pass = s.memory.measured && s.frames_over_memory == 0 && s.frames_pages_differ == 0;
    s.memory.text = formatted("memory: peak resident %.1f MiB, budget %.1f MiB; over budget on %d of %d frames",
                              mib(s.peak_resident_bytes), mib(s.memory_budget_bytes), s.frames_over_memory, s.frames);
    if (s.frames_pages_differ > 0)
        s.memory.text +=
            formatted("; the GPU's pages differ from the streamer's count on %d frames", s.frames_pages_differ);
    s.upload.measured = !lod.empty();
    s.upload.pass = s.upload.measured && s.frames_over_upload == 0;
    s.upload.text = formatted("upload: largest %.2f MiB in one frame, budget %.2f MiB; over budget on %d frames",
                              mib(s.max_upload_bytes), mib(s.upload_budget_bytes), s.frames_over_upload);
    s.pass_memory.measured = !lod.empty() && s.peak_resident_bytes > 0 && s.peak_gpu_total_bytes > 0;
    const double ratio = s.pass_memory.measured ? double(s.peak_gpu_total_bytes) / double(s.peak_resident_bytes) : 0.0;
    s.pass_memory.pass = s.pass_memory.measured && ratio <= kMaxPassMemoryRatio;
    s.pass_memory.text = formatted(
        "splat pass memory: peak %.1f MiB, %.2fx the peak resident %.1f MiB (bar %.1fx); steps 1-2 ran again on %d "
        "of %d frames; %d frames drawn in strips (at most %d)",
        mib(s.peak_gpu_total_bytes), ratio, mib(s.peak_resident_bytes), kMaxPassMemoryRatio, s.reselected_frames,
        s.frames, s.striped_frames, s.most_strips);
}

void fog_check(const std::vector<FrameRecord>& lod, ProfileSummary& s) {
    std::vector<double> fog, frame;
    for (const auto& r : lod)
        if (r.gpu_fog_ms >= 0.0) {
            fog.push_back(r.gpu_fog_ms);
            frame.push_back(r.frame_ms);
        }
    s.fog.measured = !fog.empty();
    if (!s.fog.measured) {
        s.fog.text = "fog: not drawn (run with --fog)";
        return;
    }
    const double share = median_of(fog) / median_of(frame);
    s.fog.pass = share <= kMaxFogShare;
    s.fog.text = formatted("fog: median %.2f ms of a median frame of %.1f ms, %.2f%% (bar %.0f%%)", median_of(fog),
                           median_of(frame), 100.0 * share, 100.0 * kMaxFogShare);
}

void overview_check(const std::vector<FrameRecord>& lod, const std::vector<FrameRecord>& baseline, ProfileSummary& s) {
    std::map<int, double> lod_ms;
    for (const auto& r : lod) lod_ms[r.frame] = r.frame_ms;
    double lod_sum = 0.0, base_sum = 0.0, psnr_sum = 0.0, ssim_sum = 0.0;
    int compared = 0;
    for (const auto& r : baseline) {
        if (r.segment != Segment::overview || !lod_ms.count(r.frame)) continue;
        ++s.overview_pairs;
        if (r.psnr_lod_vs_baseline >= 0.0 && r.ssim_lod_vs_baseline >= 0.0) {
            ++compared;
            psnr_sum += r.psnr_lod_vs_baseline;
            ssim_sum += r.ssim_lod_vs_baseline;
        }
        lod_sum += lod_ms[r.frame];
        base_sum += r.frame_ms;
        if (lod_ms[r.frame] > 0.0) {
            const double ratio = r.frame_ms / lod_ms[r.frame];
            s.overview_min_frame_speedup = std::min(s.overview_min_frame_speedup.value_or(ratio), ratio);
        }
    }
    s.overview.measured = s.overview_pairs > 0 && lod_sum > 0.0;
    if (!s.overview.measured) {
        s.overview.text = "overview: not measured (no baseline frames of the overview; run without --no-baseline)";
        return;
    }
    s.overview_lod_mean_ms = lod_sum / s.overview_pairs;
    s.overview_baseline_mean_ms = base_sum / s.overview_pairs;
    s.overview_speedup = base_sum / lod_sum;
    s.overview.pass = *s.overview_speedup >= kRequiredOverviewSpeedup;
    s.overview.text = formatted(
        "overview: LOD+streaming %.1f ms vs baseline (all resident) %.1f ms per frame over %d frames: "
        "%.2fx cheaper (required %.0fx; worst frame %.2fx)",
        s.overview_lod_mean_ms, s.overview_baseline_mean_ms, s.overview_pairs, *s.overview_speedup,
        kRequiredOverviewSpeedup, s.overview_min_frame_speedup.value_or(0.0));
    if (compared > 0) {
        s.overview_psnr = psnr_sum / compared;
        s.overview_ssim = ssim_sum / compared;
        s.overview.text += formatted("; image against the baseline's: PSNR %.2f dB, SSIM %.4f (mean of %d frames)",
                                     *s.overview_psnr, *s.overview_ssim, compared);
    }
}

std::vector<ReferenceFrameResult> reference_frames(const std::vector<FrameRecord>& lod,
                                                   const std::vector<FrameRecord>& baseline) {
    std::map<int, ReferenceFrameResult> frames;
    for (const auto& r : lod)
        if (r.psnr_vs_reference >= 0.0) {
            ReferenceFrameResult& f = frames[r.frame];
            f.frame = r.frame;
            f.segment = r.segment;
            f.lod_psnr = r.psnr_vs_reference;
            f.lod_ssim = r.ssim_vs_reference;
            f.seam_ratio = r.seam_ratio;
            f.seam_ratio_same_distance = r.seam_ratio_same_distance;
            f.lod_temporal_error = r.temporal_error;
        }
    for (const auto& r : baseline)
        if (const auto it = frames.find(r.frame); it != frames.end() && r.psnr_vs_reference >= 0.0) {
            it->second.baseline_psnr = r.psnr_vs_reference;
            it->second.baseline_ssim = r.ssim_vs_reference;
            it->second.baseline_seam_ratio = r.seam_ratio;
            it->second.baseline_seam_ratio_same_distance = r.seam_ratio_same_distance;
            it->second.baseline_temporal_error = r.temporal_error;
        }
    std::vector<ReferenceFrameResult> out;
    for (const auto& [frame, result] : frames) out.push_back(result);
    return out;
}

void reference_checks(ProfileSummary& s) {
    const auto& frames = s.reference_frames;
    const char* none = "no reference for this run (sample_game_harness --reference makes it)";
    // 4: never much worse than the baseline.
    int pairs = 0, worse = 0;
    double worst = 1e9;
    for (const auto& f : frames)
        if (f.baseline_psnr >= 0.0) {
            ++pairs;
            worst = std::min(worst, f.lod_psnr - f.baseline_psnr);
            worse += f.lod_psnr < f.baseline_psnr - kReferenceMaxLossDb ? 1 : 0;
        }
    s.reference_loss.measured = pairs > 0;
    s.reference_loss.pass = pairs > 0 && worse == 0;
    s.reference_loss.text =
        frames.empty() ? formatted("reference, LOD vs baseline: %s", none)
        : pairs == 0   ? std::string("reference, LOD vs baseline: no baseline frames (run without --no-baseline)")
                       : formatted(
                             "reference, LOD vs baseline: LOD PSNR - baseline PSNR >= -%.1f dB on %d of %d "
                               "reference frames (worst %+.2f dB)",
                             kReferenceMaxLossDb, pairs - worse, pairs, worst);
    // 5: the overview much better than the baseline, and good in itself.
    int overview = 0, good = 0;
    double least_gain = 1e9, least_psnr = 1e9;
    for (const auto& f : frames)
        if (f.segment == Segment::overview && f.baseline_psnr >= 0.0) {
            ++overview;
            least_gain = std::min(least_gain, f.lod_psnr - f.baseline_psnr);
            least_psnr = std::min(least_psnr, f.lod_psnr);
            good += f.lod_psnr >= f.baseline_psnr + kReferenceOverviewGainDb && f.lod_psnr >= kReferenceOverviewMinDb;
        }
    s.reference_overview.measured = overview > 0;
    s.reference_overview.pass = overview > 0 && good == overview;
    s.reference_overview.text =
        overview == 0 ? formatted("reference, overview: %s", frames.empty() ? none : "no overview frame in both runs")
                      : formatted(
                            "reference, overview: LOD >= baseline + %.0f dB and >= %.0f dB on %d of %d frames "
                            "(least gain %+.2f dB, lowest LOD PSNR %.2f dB)",
                            kReferenceOverviewGainDb, kReferenceOverviewMinDb, good, overview, least_gain, least_psnr);
    // 6: no seams.
    int measured = 0, within = 0;
    double largest = 0.0;
    for (const auto& f : frames)
        if (f.seam_ratio >= 0.0) {
            ++measured;
            largest = std::max(largest, f.seam_ratio);
            within += f.seam_ratio <= kMaxSeamRatio ? 1 : 0;
        }
    s.reference_seams.measured = measured > 0;
    s.reference_seams.pass = measured > 0 && within == measured;
    s.reference_seams.text =
        measured == 0 ? formatted("reference, seams: %s", frames.empty() ? none : "no frame shows a chunk border")
                      : formatted("reference, seams: seam_ratio <= %.2f on %d of %d frames (largest %.3f)",
                                  kMaxSeamRatio, within, measured, largest);
}

// 8: Gaussians per output pixel.
void density_check(const std::vector<FrameRecord>& lod, const WorldScale& w, ProfileSummary& s) {
    double overview_max = 0.0, path_max = 0.0;
    int overview_frame = -1, path_frame = -1;
    for (const auto& r : lod) {
        if (w.pixels == 0) break;
        const double per_pixel = static_cast<double>(r.visible) / static_cast<double>(w.pixels);
        if (per_pixel > path_max) path_max = per_pixel, path_frame = r.frame;
        if (r.segment == Segment::overview && per_pixel > overview_max)
            overview_max = per_pixel, overview_frame = r.frame;
    }
    s.scale_density.measured = w.pixels > 0 && !lod.empty();
    s.scale_density.pass = s.scale_density.measured && overview_max <= kMaxOverviewGaussiansPerPixel &&
                           path_max <= kMaxPathGaussiansPerPixel;
    s.scale_density.text = formatted(
        "scale, Gaussians per pixel: overview at most %.2f (frame %d; bar %.1f), path at most %.2f (frame %d; bar "
        "%.1f)",
        overview_max, overview_frame, kMaxOverviewGaussiansPerPixel, path_max, path_frame, kMaxPathGaussiansPerPixel);
}

// 9: work dropped before projection at ground level.
void culling_check(const std::vector<FrameRecord>& lod, ProfileSummary& s) {
    double least = 1.0;
    int ground_frames = 0;
    for (const auto& r : lod)
        if (r.segment == Segment::ground && r.considered > 0) {
            ++ground_frames;
            least = std::min(least,
                             static_cast<double>(r.culled + r.skipped + r.hidden) / static_cast<double>(r.considered));
        }
    s.scale_culling.measured = ground_frames > 0;
    s.scale_culling.pass = s.scale_culling.measured && least >= kMinGroundCulledShare;
    s.scale_culling.text = formatted(
        "scale, culling: at least %.0f%% of the resident Gaussians culled, skipped or outside the cut before "
        "projection on every ground frame (bar %.0f%%)",
        100.0 * least, 100.0 * kMinGroundCulledShare);
}

// 10: memory at the overview against the whole world.
void memory_check(const std::vector<FrameRecord>& lod, const WorldScale& w, ProfileSummary& s) {
    const auto& overview = s.segments[static_cast<std::size_t>(Segment::overview)];
    std::uint64_t peak = 0;
    for (const auto& r : lod)
        if (r.segment == Segment::overview) peak = std::max(peak, r.resident_bytes);
    s.scale_memory.measured = w.world_bytes > 0 && overview.frames > 0;
    const double share = w.world_bytes > 0 ? static_cast<double>(peak) / static_cast<double>(w.world_bytes) : 0.0;
    s.scale_memory.pass = s.scale_memory.measured && share <= kMaxOverviewResidentShare;
    s.scale_memory.text = formatted(
        "scale, memory: at the overview at most %.1f MiB resident, %.1f%% of the world's "
        "%.1f MiB (bar %.0f%%)",
        mib(peak), 100.0 * share, mib(w.world_bytes), 100.0 * kMaxOverviewResidentShare);
}

// 11: the splat budget.
void splat_budget_check(const std::vector<FrameRecord>& lod, const WorldScale& w, ProfileSummary& s) {
    std::uint64_t most = 0;
    int over = 0;
    for (const auto& r : lod) {
        most = std::max(most, r.visible);
        over += w.splat_budget > 0 && r.visible > w.splat_budget ? 1 : 0;
    }
    s.splat_budget.measured = w.splat_budget > 0 && !lod.empty();
    s.splat_budget.pass = s.splat_budget.measured && over == 0;
    s.splat_budget.text =
        w.splat_budget == 0
            ? std::string("splat budget: none set (--splat-budget N)")
            : formatted("splat budget: at most %llu drawn in a frame, budget %llu; over it on %d frames",
                        static_cast<unsigned long long>(most), static_cast<unsigned long long>(w.splat_budget), over);
}

void scale_checks(const std::vector<FrameRecord>& lod, const WorldScale& w, ProfileSummary& s) {
    const auto& ground = s.segments[static_cast<std::size_t>(Segment::ground)];
    const auto& overview = s.segments[static_cast<std::size_t>(Segment::overview)];
    // 7: the far view costs no more than the near one.
    s.scale_time.measured = ground.frames > 0 && overview.frames > 0;
    s.scale_time.pass = s.scale_time.measured && overview.median_ms <= ground.median_ms;
    s.scale_time.text =
        formatted("scale, time: overview median %.1f ms vs ground median %.1f ms (%.2fx)", overview.median_ms,
                  ground.median_ms, ground.median_ms > 0.0 ? overview.median_ms / ground.median_ms : 0.0);
    density_check(lod, w, s);
    culling_check(lod, s);
    memory_check(lod, w, s);
    splat_budget_check(lod, w, s);
}

// The runs' mean temporal error over their consecutive reference pairs.
std::string temporal_line(const ProfileSummary& s) {
    const auto& lod = s.lod_temporal;
    const auto& base = s.baseline_temporal;
    if (lod.pairs == 0) return "temporal_error: no consecutive reference frames in this run\n";
    std::string out = formatted(
        "temporal_error (mean |change - the reference's change| per pixel and channel, 0..255): LOD %.3f over %d "
        "pairs (largest %.2f, frame %d)",
        lod.mean, lod.pairs, lod.largest, lod.largest_frame);
    out += base.pairs > 0 ? formatted(", baseline %.3f over %d pairs (largest %.2f, frame %d)\n", base.mean, base.pairs,
                                      base.largest, base.largest_frame)
                          : std::string(", no baseline pairs\n");
    out += formatted(
        "pop (99.9th percentile over pixels of the same difference, per pair, 0..255): LOD peak %.2f "
        "(frame %d), mean %.2f",
        lod.pop_peak, lod.pop_peak_frame, lod.pop_mean);
    out += base.pairs > 0 ? formatted("; baseline peak %.2f (frame %d), mean %.2f\n", base.pop_peak,
                                      base.pop_peak_frame, base.pop_mean)
                          : std::string("\n");
    return out;
}

std::string reference_table(const ProfileSummary& s) {
    if (s.reference_frames.empty()) return "";
    const auto cell = [](double v, int digits) { return v < 0.0 ? std::string("-") : formatted("%.*f", digits, v); };
    std::string out =
        "\nagainst the reference (PSNR dB / SSIM; seam_ratio, seam_ratio_same_distance and temporal_error of the "
        "LOD image, and of the baseline's)\n";
    out +=
        "  frame  segment    LOD psnr    ssim | baseline psnr    ssim | seam_ratio (baseline) | same distance "
        "(baseline) | temporal (baseline)\n";
    for (const auto& f : s.reference_frames)
        out +=
            formatted("  %5d  %-9s %9s %7s | %13s %7s | %10s (%s) | %13s (%s) | %8s (%s)\n", f.frame,
                      std::string(to_string(f.segment)).c_str(), cell(f.lod_psnr, 2).c_str(),
                      cell(f.lod_ssim, 4).c_str(), cell(f.baseline_psnr, 2).c_str(), cell(f.baseline_ssim, 4).c_str(),
                      cell(f.seam_ratio, 3).c_str(), cell(f.baseline_seam_ratio, 3).c_str(),
                      cell(f.seam_ratio_same_distance, 3).c_str(), cell(f.baseline_seam_ratio_same_distance, 3).c_str(),
                      cell(f.lod_temporal_error, 2).c_str(), cell(f.baseline_temporal_error, 2).c_str());
    out += temporal_line(s);
    return out;
}

std::string verdict(const Check& check) {
    return std::string(!check.measured ? "n/a " : check.pass ? "PASS" : "FAIL") + "  " + check.text + "\n";
}

}  // namespace

TemporalErrors temporal_errors(const std::vector<FrameRecord>& rows) {
    TemporalErrors t;
    double sum = 0.0, pop_sum = 0.0;
    for (const auto& r : rows) {
        if (r.temporal_error < 0.0) continue;
        ++t.pairs;
        sum += r.temporal_error;
        if (t.largest_frame < 0 || r.temporal_error > t.largest)
            t.largest = r.temporal_error, t.largest_frame = r.frame;
        pop_sum += std::max(r.pop, 0.0);
        if (t.pop_peak_frame < 0 || r.pop > t.pop_peak) t.pop_peak = std::max(r.pop, 0.0), t.pop_peak_frame = r.frame;
    }
    t.mean = t.pairs > 0 ? sum / t.pairs : 0.0;
    t.pop_mean = t.pairs > 0 ? pop_sum / t.pairs : 0.0;
    return t;
}

double median_of(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

ProfileSummary summarize(const std::vector<FrameRecord>& lod, const std::vector<FrameRecord>& baseline,
                         std::uint64_t memory_budget_bytes, std::uint64_t upload_budget_bytes,
                         const WorldScale& scale) {
    ProfileSummary s;
    s.frames = static_cast<int>(lod.size());
    s.memory_budget_bytes = memory_budget_bytes;
    s.upload_budget_bytes = upload_budget_bytes;
    segment_times(lod, baseline, s);
    budget_checks(lod, s);
    fog_check(lod, s);
    overview_check(lod, baseline, s);
    s.reference_frames = reference_frames(lod, baseline);
    s.lod_temporal = temporal_errors(lod);
    s.baseline_temporal = temporal_errors(baseline);
    reference_checks(s);
    scale_checks(lod, scale, s);
    return s;
}

std::string format_summary(const ProfileSummary& s, const SummaryContext& context) {
    std::string out = "sample_game profile\n";
    out += "  world:    " + context.world + "\n  settings: " + context.settings + "\n\n";
    out += "frame time (ms; render to glFinish, CPU clock - compare as ratios)\n";
    out += "  segment    frames     mean   median      max | baseline frames  median  (LOD same frames)\n";
    for (std::size_t k = 0; k < kSegmentCount; ++k) {
        const SegmentTimes& t = s.segments[k];
        if (t.frames == 0) continue;
        out += formatted("  %-9s %7d %8.1f %8.1f %8.1f |", std::string(kSegmentNames[k]).c_str(), t.frames, t.mean_ms,
                         t.median_ms, t.max_ms);
        out += t.baseline_frames > 0
                   ? formatted(" %15d %7.1f  (%.1f)\n", t.baseline_frames, t.baseline_median_ms, t.lod_median_same_ms)
                   : std::string("               -\n");
    }
    if (!context.reference.empty()) out += "\nreference: " + context.reference + "\n";
    out += reference_table(s);
    out += formatted(
        "\nstreaming: %.1f MiB uploaded in all, peak GPU memory of the splat pass %.1f MiB (scene buffers %.1f + frame "
        "buffers %.1f), %llu chunk failures\n",
        mib(s.total_upload_bytes), mib(s.peak_gpu_total_bytes), mib(s.peak_scene_bytes), mib(s.peak_frame_bytes),
        static_cast<unsigned long long>(s.failures));
    out += "\nchecks (computed from the measurements)\n";
    out += "  " + verdict(s.memory) + "  " + verdict(s.pass_memory) + "  " + verdict(s.upload) + "  " +
           verdict(s.overview);
    out += "  " + verdict(s.reference_loss) + "  " + verdict(s.reference_overview) + "  " + verdict(s.reference_seams);
    out += "  " + verdict(s.scale_time) + "  " + verdict(s.scale_density) + "  " + verdict(s.scale_culling) + "  " +
           verdict(s.scale_memory) + "  " + verdict(s.splat_budget) + "  " + verdict(s.fog);
    out += formatted("\nwall time: %.0f s", context.wall_seconds);
    out += context.timing.empty() ? std::string("\n") : " (" + context.timing + ")\n";
    if (!context.outputs.empty()) {
        out += "outputs:\n";
        for (const auto& line : context.outputs) out += "  " + line + "\n";
    }
    return out;
}

}  // namespace sample_game
