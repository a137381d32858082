// Step 7 of the bake (docs/algorithms.md §4): distils each coarse level from the fine model. The target of
// a camera at level l is the level-1 model rendered at full resolution, clamped to [0, 1] and
// area-averaged by k × k (k = 4^(l−1)); the render is the `full` selection at scale k; Adam moves
// only the SH DC and opacity logit of the level-l Gaussians. Geometry and selection are fixed, so
// each camera is projected and binned once per level and each iteration is a forward and a
// backward pass of the differentiable rasteriser.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

#include "engine/core/error.h"
#include "engine/render/image.h"
#include "refine.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/lod_selection.h"
#include "splat_lod/core/parallel_for.h"
#include "splat_raster.h"

namespace splat_lod::bake::detail {
namespace {

constexpr double kAdamBeta1 = 0.9;
constexpr double kAdamBeta2 = 0.999;
constexpr double kAdamEpsilon = 1e-15;  // 3DGS's Adam epsilon
constexpr std::size_t kChunk = 4096;

// splitmix64: a fixed, portable sequence (std::shuffle's algorithm is implementation-defined).
std::uint64_t next_random(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

void shuffle(std::vector<std::size_t>& values, std::uint64_t& state) {
    for (std::size_t i = values.size(); i > 1; --i) std::swap(values[i - 1], values[next_random(state) % i]);
}

using reference::detail::sigmoid;

std::vector<double> area_average(const std::vector<double>& rgb, int width, int height, int k) {
    const int w = width / k, h = height / k;
    std::vector<double> out(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3, 0.0);
    const double inverse = 1.0 / (static_cast<double>(k) * k);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0.0;
                for (int dy = 0; dy < k; ++dy)
                    for (int dx = 0; dx < k; ++dx)
                        sum += rgb[(static_cast<std::size_t>(y * k + dy) * static_cast<std::size_t>(width) +
                                    static_cast<std::size_t>(x * k + dx)) *
                                       3 +
                                   static_cast<std::size_t>(c)];
                out[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)) * 3 +
                    static_cast<std::size_t>(c)] = sum * inverse;
            }
    return out;
}

double mse(const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
    return a.empty() ? 0.0 : sum / static_cast<double>(a.size());
}

double psnr_from_mse(double value) {
    return value > 0.0 ? -10.0 * std::log10(value) : std::numeric_limits<double>::infinity();
}

// One camera of one level: the fixed splats and what turns the parameters into their colour.
struct CameraFrame {
    RasterFrame frame;
    std::vector<double> target;    // area-averaged, k×k-downsampled
    std::vector<glm::dvec3> base;  // per splat: the colour before the clamp without the DC term
};

reference::ReferenceSettings raster_settings(const BakeOptions& options) {
    reference::ReferenceSettings settings;  // the renderer's dilation, no mip filter: as `full` draws
    settings.znear = options.znear;
    settings.background = options.background;
    settings.threads = options.threads;
    return settings;
}

// Indices of the Gaussians that the `full` selection draws in `camera` (coverage from the
// undilated covariance, docs/algorithms.md §2–3). Culling beyond the near plane is the projection's job.
std::vector<std::uint32_t> select_full(const SplatCloud& cloud, const reference::ReferenceCamera& camera,
                                       const BakeOptions& options, int coarsest) {
    const auto settings = coverage_settings(options.znear);
    const auto frame = reference::detail::make_instance_frame(cloud, glm::dmat4(1.0), camera, settings, 0);
    LodRule rule = options.rule;
    rule.mode = plugin_msgs::LodMode::full;  // lod_selected: the hard rule
    std::vector<std::uint8_t> keep(cloud.size(), 0);
    const std::size_t tasks = (cloud.size() + kChunk - 1) / kChunk;
    reference::detail::parallel_for(
        tasks, reference::detail::resolve_thread_count(options.threads), [&](std::size_t t) {
            for (std::size_t i = t * kChunk; i < std::min(cloud.size(), (t + 1) * kChunk); ++i) {
                const double coverage =
                    projected_coverage(reference::detail::project_in_frame(cloud, i, frame, camera, settings));
                if (coverage < 0.0) continue;
                keep[i] = lod_selected(rule, cloud.lod_level[i], coverage, cloud.coverage_min[i], cloud.coverage_max[i],
                                       coarsest);
            }
        });
    std::vector<std::uint32_t> selected;
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (keep[i]) selected.push_back(static_cast<std::uint32_t>(i));
    return selected;
}

// Per camera: the fixed geometry and the `full` selection at the level's scale, the target, and
// each splat's colour without its DC term (the SH rest along the view + 0.5, before the clamp).
std::vector<CameraFrame> build_frames(const SplatCloud& cloud, int level,
                                      const std::vector<reference::ReferenceCamera>& cameras,
                                      const std::vector<std::vector<double>>& targets, const BakeOptions& options,
                                      LevelSummary* summary) {
    const int k = level_scale(level);
    const int coarsest = *std::max_element(cloud.lod_level.begin(), cloud.lod_level.end());
    std::vector<CameraFrame> frames;
    for (std::size_t c = 0; c < cameras.size(); ++c) {
        const auto camera = scaled_camera(cameras[c], k);
        const auto selected = select_full(cloud, camera, options, coarsest);
        if (summary != nullptr)
            for (const std::uint32_t i : selected)
                summary->refine_drawn_per_level[cloud.lod_level[i] - 1] += 1.0 / static_cast<double>(cameras.size());
        RasterFrame frame(project_for_raster(cloud, selected, camera, raster_settings(options), options.threads),
                          camera.width, camera.height);
        std::vector<glm::dvec3> base(frame.splats().size());
        for (std::size_t j = 0; j < base.size(); ++j) {
            const std::size_t i = frame.splats()[j].id;
            const glm::dvec3 direction = glm::dvec3(cloud.positions[i]) - camera.position;
            base[j] = reference::sh_colour_unclamped(cloud, i, cloud.sh_degree, direction) -
                      static_cast<double>(kShC0) * glm::dvec3(cloud.sh_dc[i]);
        }
        frames.push_back(
            {std::move(frame), area_average(targets[c], cameras[c].width, cameras[c].height, k), std::move(base)});
    }
    return frames;
}

// The level's Gaussians and the parameters Adam moves: `slot` maps a cloud index to its place in
// `members`, `dc` and `logit`, or is −1 for the other levels' Gaussians, which stay as the cloud holds them.
struct LevelParameters {
    std::vector<std::int64_t> slot;
    std::vector<std::size_t> members;
    std::vector<glm::dvec3> dc;
    std::vector<double> logit;
};

LevelParameters level_members(const SplatCloud& cloud, int level) {
    LevelParameters p;
    p.slot.assign(cloud.size(), -1);
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (cloud.lod_level[i] == level) {
            p.slot[i] = static_cast<std::int64_t>(p.members.size());
            p.members.push_back(i);
        }
    return p;
}

// The starting parameters: the cloud's own.
void load_parameters(const SplatCloud& cloud, LevelParameters& p) {
    p.dc.resize(p.members.size());
    p.logit.resize(p.members.size());
    for (std::size_t m = 0; m < p.members.size(); ++m) {
        p.dc[m] = glm::dvec3(cloud.sh_dc[p.members[m]]);
        p.logit[m] = cloud.opacity_logits[p.members[m]];
    }
}

// What the rasteriser reads for one frame, reused from frame to frame so that nothing is reallocated.
struct FrameInputs {
    std::vector<glm::dvec3> colour;
    std::vector<double> opacity;
    std::vector<glm::dvec3> before_clamp;
};

// Current parameters of every splat of a frame, from the cloud (the level's from `dc`/`logit`).
void load_inputs(const CameraFrame& f, const SplatCloud& cloud, const LevelParameters& p, FrameInputs& in) {
    const auto& splats = f.frame.splats();
    in.colour.resize(splats.size());
    in.opacity.resize(splats.size());
    in.before_clamp.resize(splats.size());
    for (std::size_t j = 0; j < splats.size(); ++j) {
        const std::size_t i = splats[j].id;
        const std::int64_t s = p.slot[i];
        const glm::dvec3 d = s >= 0 ? p.dc[static_cast<std::size_t>(s)] : glm::dvec3(cloud.sh_dc[i]);
        const double l = s >= 0 ? p.logit[static_cast<std::size_t>(s)] : static_cast<double>(cloud.opacity_logits[i]);
        in.before_clamp[j] = f.base[j] + static_cast<double>(kShC0) * d;
        in.colour[j] = glm::max(in.before_clamp[j], glm::dvec3(0.0));
        in.opacity[j] = sigmoid(l);
    }
}

double mean_psnr(const std::vector<CameraFrame>& frames, const SplatCloud& cloud, const LevelParameters& p,
                 const BakeOptions& options, FrameInputs& in) {
    double sum = 0.0;
    for (const auto& f : frames) {
        load_inputs(f, cloud, p, in);
        sum += psnr_from_mse(
            mse(render_forward(f.frame, in.colour, in.opacity, options.background, options.threads).rgb, f.target));
    }
    return sum / static_cast<double>(frames.size());
}

// `rgb` as an 8-bit PNG of the given size, each channel clamped to [0, 1].
void save_debug_png(const std::vector<double>& rgb, int width, int height, const std::string& path) {
    engine::Image out;
    out.width = width;
    out.height = height;
    out.rgba.resize(static_cast<std::size_t>(out.width) * out.height * 4, 255);
    for (std::size_t p = 0; p < rgb.size() / 3; ++p)
        for (int ch = 0; ch < 3; ++ch)
            out.rgba[p * 4 + ch] =
                static_cast<std::uint8_t>(std::lround(std::clamp(rgb[p * 3 + ch], 0.0, 1.0) * 255.0));
    engine::write_png(path, out);
}

// With a debug image folder: the first camera's render as `tag` and its target, to see what Adam did.
void dump_images(const std::vector<CameraFrame>& frames, const SplatCloud& cloud, const LevelParameters& p,
                 const BakeOptions& options, int level, const std::string& tag, FrameInputs& in) {
    if (options.debug_image_dir.empty()) return;
    const std::string dir = options.debug_image_dir;
    const auto& f = frames.front();
    load_inputs(f, cloud, p, in);
    const auto image = render_forward(f.frame, in.colour, in.opacity, options.background, options.threads);
    const std::string prefix = dir + "/level" + std::to_string(level) + "_";
    save_debug_png(image.rgb, image.width, image.height, prefix + tag + ".png");
    save_debug_png(f.target, image.width, image.height, prefix + "target" + ".png");
}

// For comparison: level 1 alone, unfiltered (the baseline renderer), on the same cameras.
double baseline_psnr(const SplatCloud& cloud, const std::vector<reference::ReferenceCamera>& cameras,
                     const std::vector<CameraFrame>& frames, int k, const BakeOptions& options) {
    const int threads = options.threads;
    std::vector<std::uint32_t> fine_indices;
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (cloud.lod_level[i] == 1) fine_indices.push_back(static_cast<std::uint32_t>(i));
    double sum = 0.0;
    for (std::size_t c = 0; c < cameras.size(); ++c) {
        const auto camera = scaled_camera(cameras[c], k);
        RasterFrame frame(project_for_raster(cloud, fine_indices, camera, raster_settings(options), threads),
                          camera.width, camera.height);
        sum += psnr_from_mse(
            mse(render_forward(frame, frame.colours(), frame.opacities(), options.background, threads).rgb,
                frames[c].target));
    }
    return sum / static_cast<double>(cameras.size());
}

// Adam's moments, and the gradients of the current step, per member of the level.
struct AdamState {
    explicit AdamState(std::size_t n)
        : m_dc(n, glm::dvec3(0.0)), v_dc(n, glm::dvec3(0.0)), m_logit(n, 0.0), v_logit(n, 0.0), g_dc(n), g_logit(n) {}

    std::vector<glm::dvec3> m_dc, v_dc;
    std::vector<double> m_logit, v_logit;
    std::vector<glm::dvec3> g_dc;
    std::vector<double> g_logit;
    std::vector<glm::dvec3> d_colour;  // per splat of the frame
    std::vector<double> d_opacity;
};

// The gradients of the frame's loss with respect to the level's parameters (`in` loaded for `f`).
void level_gradients(const CameraFrame& f, const FrameInputs& in, const LevelParameters& p, const BakeOptions& options,
                     AdamState& adam) {
    const RasterImage image = render_forward(f.frame, in.colour, in.opacity, options.background, options.threads);
    // L = mean over pixels and channels of (C − target)².
    std::vector<double> dl(image.rgb.size());
    const double scale = 2.0 / static_cast<double>(image.rgb.size());
    for (std::size_t q = 0; q < dl.size(); ++q) dl[q] = scale * (image.rgb[q] - f.target[q]);
    adam.d_colour.assign(in.colour.size(), glm::dvec3(0.0));
    adam.d_opacity.assign(in.colour.size(), 0.0);
    render_backward(f.frame, in.colour, in.opacity, options.background, dl, adam.d_colour, adam.d_opacity,
                    options.threads);

    std::fill(adam.g_dc.begin(), adam.g_dc.end(), glm::dvec3(0.0));
    std::fill(adam.g_logit.begin(), adam.g_logit.end(), 0.0);
    for (std::size_t j = 0; j < in.colour.size(); ++j) {
        const std::int64_t s = p.slot[f.frame.splats()[j].id];
        if (s < 0) continue;
        const auto m = static_cast<std::size_t>(s);
        adam.g_dc[m] += d_sh_dc_from_d_colour(adam.d_colour[j], in.before_clamp[j]);
        adam.g_logit[m] += d_logit_from_d_opacity(adam.d_opacity[j], p.logit[m]);
    }
}

// Adam (Kingma & Ba) with bias correction, every parameter of the level each step.
void adam_step(int iteration, const BakeOptions& options, AdamState& adam, LevelParameters& p) {
    const double t = iteration + 1.0;
    const double c1 = 1.0 - std::pow(kAdamBeta1, t), c2 = 1.0 - std::pow(kAdamBeta2, t);
    for (std::size_t m = 0; m < p.members.size(); ++m) {
        adam.m_dc[m] = kAdamBeta1 * adam.m_dc[m] + (1.0 - kAdamBeta1) * adam.g_dc[m];
        adam.v_dc[m] = kAdamBeta2 * adam.v_dc[m] + (1.0 - kAdamBeta2) * adam.g_dc[m] * adam.g_dc[m];
        p.dc[m] -= options.learning_rate_dc * (adam.m_dc[m] / c1) / (glm::sqrt(adam.v_dc[m] / c2) + kAdamEpsilon);
        adam.m_logit[m] = kAdamBeta1 * adam.m_logit[m] + (1.0 - kAdamBeta1) * adam.g_logit[m];
        adam.v_logit[m] = kAdamBeta2 * adam.v_logit[m] + (1.0 - kAdamBeta2) * adam.g_logit[m] * adam.g_logit[m];
        p.logit[m] -=
            options.learning_rate_opacity * (adam.m_logit[m] / c1) / (std::sqrt(adam.v_logit[m] / c2) + kAdamEpsilon);
        p.logit[m] = std::clamp(p.logit[m], -options.logit_clamp, options.logit_clamp);
    }
}

// The refinement's iterations: one camera each, a fresh fixed-seed permutation per pass over the cameras.
void optimise(const std::vector<CameraFrame>& frames, const SplatCloud& cloud, const BakeOptions& options, int level,
              const std::string& stage, LevelParameters& p, FrameInputs& in) {
    AdamState adam(p.members.size());
    std::vector<std::size_t> order(frames.size());
    std::uint64_t random_state = options.seed * 0x2545f4914f6cdd1dULL + static_cast<std::uint64_t>(level);

    for (int iteration = 0; iteration < options.refine_iterations; ++iteration) {
        const std::size_t position = static_cast<std::size_t>(iteration) % frames.size();
        if (position == 0) {
            std::iota(order.begin(), order.end(), std::size_t{0});
            shuffle(order, random_state);
        }
        if (options.progress && iteration % 20 == 0)
            options.progress(stage, 0.2 + 0.8 * iteration / static_cast<double>(options.refine_iterations));
        const CameraFrame& f = frames[order[position]];
        load_inputs(f, cloud, p, in);
        level_gradients(f, in, p, options, adam);
        adam_step(iteration, options, adam, p);
    }
}

}  // namespace

double Refiner::evaluate(const SplatCloud& cloud, int level) const {
    const auto frames = build_frames(cloud, level, cameras_, targets_, options_, nullptr);
    double sum = 0.0;
    for (const auto& f : frames)
        sum += psnr_from_mse(mse(
            render_forward(f.frame, f.frame.colours(), f.frame.opacities(), options_.background, options_.threads).rgb,
            f.target));
    return frames.empty() ? 0.0 : sum / static_cast<double>(frames.size());
}

Refiner::Refiner(const SplatCloud& fine, const std::vector<reference::ReferenceCamera>& cameras,
                 const BakeOptions& options)
    : options_(options) {
    for (const std::size_t i : refinement_cameras(cameras, options.refine_cameras)) cameras_.push_back(cameras[i]);
    const reference::ReferenceInstance instance{&fine, glm::dmat4(1.0), kMaxShDegree};
    for (std::size_t c = 0; c < cameras_.size(); ++c) {
        if (options_.progress) options_.progress("refine targets", static_cast<double>(c) / cameras_.size());
        const auto image = reference::render_reference({&instance, 1}, cameras_[c], raster_settings(options_));
        std::vector<double> rgb = image.rgb;
        for (double& v : rgb) v = std::clamp(v, 0.0, 1.0);
        targets_.push_back(std::move(rgb));
    }
}

void Refiner::refine_level(SplatCloud& cloud, int level, LevelSummary& summary) const {
    const int k = level_scale(level);
    const std::string stage = "refine level " + std::to_string(level);

    LevelParameters p = level_members(cloud, level);
    if (p.members.empty()) return;

    const std::vector<CameraFrame> frames = build_frames(cloud, level, cameras_, targets_, options_, &summary);
    load_parameters(cloud, p);
    FrameInputs in;
    summary.refine_psnr_before = mean_psnr(frames, cloud, p, options_, in);
    dump_images(frames, cloud, p, options_, level, "before", in);
    summary.refine_psnr_baseline = baseline_psnr(cloud, cameras_, frames, k, options_);

    optimise(frames, cloud, options_, level, stage, p, in);

    for (std::size_t m = 0; m < p.members.size(); ++m) {
        cloud.sh_dc[p.members[m]] = glm::vec3(p.dc[m]);
        cloud.opacity_logits[p.members[m]] = static_cast<float>(p.logit[m]);
    }
    summary.refine_iterations = options_.refine_iterations;
    summary.refine_psnr_after = mean_psnr(frames, cloud, p, options_, in);
    dump_images(frames, cloud, p, options_, level, "after", in);
}

reference::ReferenceCamera scaled_camera(const reference::ReferenceCamera& camera, int k) {
    reference::ReferenceCamera scaled = camera;
    scaled.fx /= k;
    scaled.fy /= k;
    scaled.cx /= k;
    scaled.cy /= k;
    scaled.width = camera.width / k;
    scaled.height = camera.height / k;
    return scaled;
}

std::vector<std::size_t> refinement_cameras(const std::vector<reference::ReferenceCamera>& cameras, int limit) {
    std::vector<std::size_t> usable;
    for (std::size_t i = 0; i < cameras.size(); ++i) {
        const auto& c = cameras[i];
        if (c.width % 64 != 0 || c.height % 64 != 0) continue;
        if (!usable.empty()) {
            const auto& first = cameras[usable.front()];
            if (c.fx != first.fx || c.fy != first.fy || c.width != first.width || c.height != first.height) continue;
        }
        usable.push_back(i);
    }
    if (limit <= 0 || usable.size() <= static_cast<std::size_t>(limit)) return usable;
    std::vector<std::size_t> spread;
    for (int j = 0; j < limit; ++j)
        spread.push_back(usable[static_cast<std::size_t>(j) * usable.size() / static_cast<std::size_t>(limit)]);
    return spread;
}

// Step 7 for every coarse level that gained Gaussians, finest first (each is refined with the finer
// ones already settled). Returns the refiner that ran (its targets serve the final check), or null.
const Refiner* refine_levels(SplatCloud& cloud, const SplatCloud& fine,
                             const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options,
                             const Refiner* shared_refiner, std::optional<Refiner>& own_refiner, BakeSummary& summary,
                             StageClock& clock) {
    const bool any_added =
        std::any_of(summary.levels.begin(), summary.levels.end(), [](const LevelSummary& l) { return l.added > 0; });
    if (options.refine_iterations == 0 || !any_added) return nullptr;
    const Refiner* refiner = shared_refiner;
    if (refiner == nullptr) {
        clock.start("refine targets");
        refiner = &own_refiner.emplace(fine, cameras, options);
    }
    if (!refiner->usable())
        summary.warnings.push_back("no camera has image sides divisible by 64: the refinement was skipped");
    for (auto& level_summary : summary.levels) {
        if (level_summary.added == 0 || !refiner->usable()) continue;
        clock.start("refine level " + std::to_string(level_summary.level));
        refiner->refine_level(cloud, level_summary.level, level_summary);
    }
    return refiner;
}

}  // namespace splat_lod::bake::detail
