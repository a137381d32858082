// The bake's driver: runs docs/algorithms.md §4 steps 1–7 in order, times each stage and reports progress.
#include "splat_lod/bake/bake.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>
#include <utility>

#include "bake_steps.h"
#include "engine/core/error.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/parallel_for.h"

namespace splat_lod::bake {
namespace {

std::size_t peak_resident_bytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) {
            std::istringstream fields(line.substr(6));
            std::size_t kib = 0;
            fields >> kib;
            return kib * 1024;
        }
    return 0;
}

class StageClock {
public:
    StageClock(BakeSummary& summary, const BakeOptions& options) : summary_(summary), options_(options) {}
    void start(const std::string& stage) {
        stop();
        stage_ = stage;
        begin_ = std::chrono::steady_clock::now();
        report(0.0);
    }
    void report(double fraction) const {
        if (options_.progress && !stage_.empty()) options_.progress(stage_, std::clamp(fraction, 0.0, 1.0));
    }
    void stop() {
        if (stage_.empty()) return;
        report(1.0);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
        summary_.stages.push_back({stage_, seconds});
        stage_.clear();
    }

private:
    BakeSummary& summary_;
    const BakeOptions& options_;
    std::string stage_;
    std::chrono::steady_clock::time_point begin_;
};

using CellMembers = detail::LevelMembers;

// Steps 1–3 for one level: the Gaussians of finer levels that some camera sees smaller than S_T at
// the level's scale, by cell. Cell g's members are members[starts[g] .. starts[g + 1]).
CellMembers small_by_cell(const SplatCloud& cloud, const detail::CoverageTable& table, int level,
                          const detail::Normaliser& normaliser, const std::vector<reference::ReferenceCamera>& cameras,
                          const BakeOptions& options, LevelSummary& summary) {
    const int scale = level_scale(level);
    const int cells = (options.grid_cells + level - 1) / level;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;  // (cell, Gaussian)
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (cloud.lod_level[i] >= level) continue;
        double smallest = std::numeric_limits<double>::infinity();
        bool seen = false;
        for (const float s : table.row(i))
            if (s >= 0.0f) {
                seen = true;
                smallest = std::min(smallest, static_cast<double>(s) / scale);
            }
        if (!seen) continue;
        ++summary.candidates;
        if (smallest >= options.rule.size_threshold_px) continue;
        ++summary.small;
        keyed.emplace_back(detail::cell_key(glm::dvec3(cloud.positions[i]), level, cells, normaliser, cameras, options),
                           static_cast<std::uint32_t>(i));
    }
    // Sorted by (cell, index): the cells, their members and the first member (the quaternion
    // hemisphere) do not depend on anything but the input.
    std::sort(keyed.begin(), keyed.end());
    CellMembers out;
    for (std::size_t j = 0; j < keyed.size(); ++j)
        if (j == 0 || keyed[j].first != keyed[j - 1].first) out.starts.push_back(j);
    out.starts.push_back(keyed.size());
    out.members.resize(keyed.size());
    for (std::size_t j = 0; j < keyed.size(); ++j) out.members[j] = keyed[j].second;
    return out;
}

// Steps 1–5 for one level: pools the Gaussians of finer levels that are small at its scale into
// one new Gaussian per grid cell, enlarged towards S_T, and appends them (and their coverage).
// Returns the cells' members; the level's Gaussians start at its `first`.
CellMembers build_level(SplatCloud& cloud, detail::CoverageTable& table, int level,
                        const detail::Normaliser& normaliser, const std::vector<reference::ReferenceCamera>& cameras,
                        const BakeOptions& options, LevelSummary& summary, const StageClock& clock) {
    const int scale = level_scale(level);
    summary.level = level;
    summary.scale = scale;
    CellMembers cells = small_by_cell(cloud, table, level, normaliser, cameras, options, summary);
    const std::vector<std::uint32_t>& members = cells.members;
    const std::vector<std::size_t>& starts = cells.starts;
    const std::size_t groups = starts.size() - 1;
    summary.added = groups;
    cells.first = cloud.size();
    if (groups == 0) return cells;
    const std::size_t first_new = cloud.size();
    cloud.resize(first_new + groups);
    std::vector<double> factors(groups, 1.0);
    reference::detail::parallel_for(
        groups, reference::detail::resolve_thread_count(options.threads), [&](std::size_t g) {
            const std::span<const std::uint32_t> cell(members.data() + starts[g], starts[g + 1] - starts[g]);
            const std::size_t out = first_new + g;
            cloud.lod_level[out] = static_cast<std::uint8_t>(level);
            if (options.pooling == PoolingRule::moments) {
                detail::pool_moments(cloud, cell, cloud, out);
                detail::thicken(cloud, out, options.min_axis_ratio);
                return;
            }
            detail::pool(cloud, cell, cloud, out);
            detail::thicken(cloud, out, options.min_axis_ratio);
            const double s_avg = detail::mean_median_coverage(table, cell, scale);
            factors[g] = detail::enlargement(options.rule.size_threshold_px, s_avg, options.max_enlargement);
            cloud.log_scales[out] += glm::vec3(static_cast<float>(std::log(factors[g])));
        });
    double sum = 0.0;
    for (const double f : factors) {
        sum += f;
        if (f >= options.max_enlargement) ++summary.at_max_enlargement;
    }
    summary.mean_enlargement = sum / static_cast<double>(groups);
    clock.report(0.5);
    table.append(cloud, first_new, cameras, options.znear, options.threads);
    return cells;
}

// Step 6, and with BakeOptions::member_ranges the cap of each coarse Gaussian's coverage_max at
// the coverage where its members stop being drawn.
void set_ranges(SplatCloud& cloud, const detail::CoverageTable& table, const std::vector<CellMembers>& levels,
                const BakeOptions& options) {
    detail::set_coverage_ranges(cloud, table, options.range_low_percentile, options.range_high_percentile);
    if (options.member_ranges) detail::cap_coverage_max(cloud, table, levels, options);
}

}  // namespace

void validate(const BakeOptions& o) {
    const auto bad = [](const std::string& what) { engine::fail("bake options: " + what); };
    if (o.coarsest_level < 1 || o.coarsest_level > kMaxLevel) bad("the coarsest level must be 1..4");
    if (!(o.rule.size_threshold_px > 0.0f) || !std::isfinite(o.rule.size_threshold_px)) bad("S_T must be positive");
    if (!(o.rule.rel_min > 0.0f && o.rule.rel_max > 0.0f) || !std::isfinite(o.rule.rel_min + o.rule.rel_max))
        bad("S_rel_min/max must be positive");
    if (!(o.znear > 0.0) || !std::isfinite(o.znear)) bad("znear must be positive");
    if (o.grid_cells < 1 || o.grid_cells > 2'000'000) bad("grid cells must be 1..2000000");
    if (!(o.max_enlargement >= 1.0) || !std::isfinite(o.max_enlargement))
        bad("the enlargement clamp must be at least 1");
    if (!(o.range_low_percentile >= 0.0 && o.range_low_percentile <= o.range_high_percentile &&
          o.range_high_percentile <= 100.0))
        bad("range percentiles must satisfy 0 <= low <= high <= 100");
    if (o.refine_iterations < 0 || o.refine_cameras < 0) bad("refinement iterations and cameras must not be negative");
    if (!(o.learning_rate_dc >= 0.0 && o.learning_rate_opacity >= 0.0) ||
        !std::isfinite(o.learning_rate_dc + o.learning_rate_opacity))
        bad("learning rates must be finite and not negative");
    if (!(o.logit_clamp > 0.0) || !std::isfinite(o.logit_clamp)) bad("the logit clamp must be positive");
    if (!(o.view_margin >= 0.0 && o.view_margin <= 4.0)) bad("the view margin must be in [0, 4]");
    if (!(o.min_axis_ratio >= 0.0 && o.min_axis_ratio <= 1.0)) bad("the axis ratio floor must be in [0, 1]");
}

double BakeSummary::added_fraction() const {
    if (input_gaussians == 0) return 0.0;
    return static_cast<double>(output_gaussians - input_gaussians) / static_cast<double>(input_gaussians);
}

namespace {

constexpr double kRecipeMargin = 0.5;  // dB of mean level PSNR the grid recipe must win by

std::string recipe_name(const BakeOptions& options) {
    char text[96];
    std::snprintf(text, sizeof text, "%s cells, enlargement <= %g",
                  options.cells == CellRule::grid ? "grid" : "adaptive", options.max_enlargement);
    return text;
}

// `shared_refiner`: the refinement's targets when a caller bakes the same scene more than once
// (they depend only on the fine model and the cameras); null: made here when needed.
SplatCloud bake_once(const SplatCloud& fine, const std::vector<reference::ReferenceCamera>& cameras,
                     const BakeOptions& options, const detail::Refiner* shared_refiner, BakeSummary* summary_out);

}  // namespace

namespace {

struct RecipeBake {
    SplatCloud cloud;
    BakeSummary summary;
};

// Both recipes, side by side, each on half the threads (a bake's bytes do not depend on its thread
// count), sharing the refinement targets; their progress lines are serialised. The first error thrown
// by either is rethrown once both are done.
std::array<RecipeBake, 2> bake_recipes(const SplatCloud& fine, const std::vector<reference::ReferenceCamera>& cameras,
                                       const BakeOptions& options, std::array<BakeOptions, 2>& recipes,
                                       const detail::Refiner& refiner) {
    const int threads = std::max(1, reference::detail::resolve_thread_count(options.threads) / 2);
    std::mutex progress_mutex;
    for (BakeOptions& recipe : recipes) {
        recipe.threads = threads;
        if (options.progress)
            recipe.progress = [&, name = recipe_name(recipe)](const std::string& stage, double fraction) {
                const std::lock_guard lock(progress_mutex);
                options.progress(name + ": " + stage, fraction);
            };
    }
    std::array<RecipeBake, 2> out;
    std::array<std::exception_ptr, 2> errors;
    const auto bake = [&](std::size_t k) {
        try {
            out[k].cloud = bake_once(fine, cameras, recipes[k], &refiner, &out[k].summary);
        } catch (...) {
            errors[k] = std::current_exception();
        }
    };
    std::thread second(bake, 1);
    bake(0);
    second.join();
    for (const auto& error : errors)
        if (error) std::rethrow_exception(error);
    return out;
}

double mean_final_psnr(const BakeSummary& summary) {
    double score = 0.0;
    for (const auto& level : summary.levels) score += level.final_psnr / static_cast<double>(summary.levels.size());
    return score;
}

double stage_seconds(const BakeSummary& summary) {
    double seconds = 0.0;
    for (const auto& stage : summary.stages) seconds += stage.seconds;
    return seconds;
}

}  // namespace

SplatCloud bake_lod(const SplatCloud& fine, const std::vector<reference::ReferenceCamera>& cameras,
                    const BakeOptions& options, BakeSummary* summary_out) {
    validate(options);
    if (!options.choose_recipe || options.refine_iterations == 0 || options.coarsest_level < 2)
        return bake_once(fine, cameras, options, nullptr, summary_out);
    std::array<BakeOptions, 2> recipes{options, options};
    recipes[0].cells = CellRule::adaptive;
    recipes[0].max_enlargement = 8.0;
    recipes[1].cells = CellRule::grid;
    recipes[1].max_enlargement = 32.0;
    const auto targets_start = std::chrono::steady_clock::now();
    const detail::Refiner refiner(fine, cameras, options);
    const double targets_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - targets_start).count();
    std::array<RecipeBake, 2> baked = bake_recipes(fine, cameras, options, recipes, refiner);
    // The adaptive recipe (first) adds fewer Gaussians; the grid one must be clearly better to be kept
    // (on the garden, 0.2 dB better on the bake cameras was 2.4 dB worse on held-out views at 16×).
    const std::array<double, 2> scores{mean_final_psnr(baked[0].summary), mean_final_psnr(baked[1].summary)};
    const std::size_t best = scores[1] > scores[0] + kRecipeMargin;
    BakeSummary summary = std::move(baked[best].summary);
    summary.recipe = recipe_name(recipes[best]);
    for (std::size_t k = 0; k < 2; ++k) summary.recipe_scores.emplace_back(recipe_name(recipes[k]), scores[k]);
    const double other = stage_seconds(baked[1 - best].summary);
    summary.stages.insert(summary.stages.begin(), {"refine targets (both recipes)", targets_seconds});
    summary.stages.push_back({"the other recipe", other});
    summary.peak_memory_bytes = peak_resident_bytes();
    if (summary_out) *summary_out = std::move(summary);
    return std::move(baked[best].cloud);
}

namespace {

void check_input(const SplatCloud& fine, const std::vector<reference::ReferenceCamera>& cameras) {
    if (fine.empty()) engine::fail("bake: the scene has no Gaussians");
    if (cameras.empty()) engine::fail("bake: no cameras");
    fine.check_consistent();
    if (fine.has_lod_attributes())
        engine::fail(
            "bake: the scene already has LOD attributes (levels above 1 or coverage ranges); bake the original "
            "level-1 scene");
    for (const auto& camera : cameras) reference::detail::check_camera(camera, "bake");
}

// Step 1's table: the coverage of every Gaussian in every camera. Fails when no camera sees any.
detail::CoverageTable measure_coverage(const SplatCloud& cloud, const std::vector<reference::ReferenceCamera>& cameras,
                                       const BakeOptions& options) {
    detail::CoverageTable table(cameras.size(), options.view_margin);
    table.append(cloud, 0, cameras, options.znear, options.threads);
    std::size_t seen = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto row = table.row(i);
        seen += std::any_of(row.begin(), row.end(), [](float s) { return s >= 0.0f; });
    }
    if (seen == 0)
        engine::fail("bake: none of the " + std::to_string(cameras.size()) + " cameras sees any of the " +
                     std::to_string(cloud.size()) +
                     " Gaussians (in front of it, centre inside its image, opacity above 1/255)");
    return table;
}

// Step 7 for every coarse level that gained Gaussians, finest first (each is refined with the finer
// ones already settled). Returns the refiner that ran (its targets serve the final check), or null.
const detail::Refiner* refine_levels(SplatCloud& cloud, const SplatCloud& fine,
                                     const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options,
                                     const detail::Refiner* shared_refiner, std::optional<detail::Refiner>& own_refiner,
                                     BakeSummary& summary, StageClock& clock) {
    const bool any_added =
        std::any_of(summary.levels.begin(), summary.levels.end(), [](const LevelSummary& l) { return l.added > 0; });
    if (options.refine_iterations == 0 || !any_added) return nullptr;
    const detail::Refiner* refiner = shared_refiner;
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

SplatCloud bake_once(const SplatCloud& fine, const std::vector<reference::ReferenceCamera>& cameras,
                     const BakeOptions& options, const detail::Refiner* shared_refiner, BakeSummary* summary_out) {
    check_input(fine, cameras);
    BakeSummary summary;
    summary.input_gaussians = fine.size();
    summary.cameras = cameras.size();
    StageClock clock(summary, options);

    SplatCloud cloud = fine;
    clock.start("coverage");
    detail::CoverageTable table = measure_coverage(cloud, cameras, options);
    const detail::Normaliser normaliser = detail::make_normaliser(cameras, cloud);
    summary.normalisation_radius = normaliser.radius;
    summary.radius_from_gaussians = normaliser.from_gaussians;

    std::vector<CellMembers> members;
    for (int level = 2; level <= options.coarsest_level; ++level) {
        clock.start("level " + std::to_string(level));
        LevelSummary level_summary;
        members.push_back(build_level(cloud, table, level, normaliser, cameras, options, level_summary, clock));
        summary.levels.push_back(level_summary);
    }

    clock.start("ranges");
    set_ranges(cloud, table, members, options);

    std::optional<detail::Refiner> own_refiner;
    const detail::Refiner* refiner =
        refine_levels(cloud, fine, cameras, options, shared_refiner, own_refiner, summary, clock);
    const bool refined = std::any_of(summary.levels.begin(), summary.levels.end(),
                                     [](const LevelSummary& l) { return l.refine_iterations > 0; });
    if (refined && options.ranges_after_refine) {
        // The refinement lowers opacities, which shrinks coverage: the ranges must describe the
        // Gaussians as they are drawn.
        clock.start("ranges after refinement");
        table.recompute(cloud, cameras, options.znear, options.threads);
        set_ranges(cloud, table, members, options);
    }
    table = detail::CoverageTable();
    if (refined) {
        // Each level as the finished asset draws it, on the refinement's cameras.
        clock.start("final check");
        for (auto& level_summary : summary.levels)
            level_summary.final_psnr = refiner->evaluate(cloud, level_summary.level);
    }
    own_refiner.reset();

    clock.start("order");
    SplatCloud result = cloud.permuted(detail::output_order(cloud, normaliser));
    clock.stop();

    summary.output_gaussians = result.size();
    for (std::size_t i = 0; i < result.size(); ++i) summary.unseen += result.coverage_min[i] < 0.0f;
    summary.peak_memory_bytes = peak_resident_bytes();
    if (summary_out) *summary_out = std::move(summary);
    return result;
}

}  // namespace

std::string format_summary(const BakeSummary& s) {
    std::ostringstream out;
    char line[256];
    std::snprintf(line, sizeof line, "input %zu Gaussians, %zu cameras, output %zu (+%.2f%%), %zu seen by no camera\n",
                  s.input_gaussians, s.cameras, s.output_gaussians, 100.0 * s.added_fraction(), s.unseen);
    out << line;
    std::snprintf(line, sizeof line, "normalisation radius B = %.4g (%s)\n", s.normalisation_radius,
                  s.radius_from_gaussians ? "from the Gaussians: the cameras coincide" : "from the camera positions");
    out << line;
    for (const auto& warning : s.warnings) out << "warning: " << warning << '\n';
    if (!s.recipe.empty()) {
        out << "recipe: " << s.recipe << " (mean final PSNR of the levels:";
        const char* separator = " ";
        for (const auto& [name, score] : s.recipe_scores) {
            std::snprintf(line, sizeof line, "%s%s %.2f dB", separator, name.c_str(), score);
            out << line;
            separator = "; ";
        }
        out << ")\n";
    }
    for (const auto& l : s.levels) {
        std::snprintf(
            line, sizeof line,
            "level %d (scale %d): %zu candidates, %zu small, %zu added; enlargement mean %.2f, %zu at the clamp",
            l.level, l.scale, l.candidates, l.small, l.added, l.mean_enlargement, l.at_max_enlargement);
        out << line;
        if (l.refine_iterations > 0) {
            std::snprintf(line, sizeof line, "; refined %d iterations: %.2f -> %.2f dB (baseline %.2f dB)",
                          l.refine_iterations, l.refine_psnr_before, l.refine_psnr_after, l.refine_psnr_baseline);
            out << line;
            std::snprintf(line, sizeof line, "; final %.2f dB", l.final_psnr);
            out << line;
            std::snprintf(line, sizeof line, "; drawn per level %.0f/%.0f/%.0f/%.0f", l.refine_drawn_per_level[0],
                          l.refine_drawn_per_level[1], l.refine_drawn_per_level[2], l.refine_drawn_per_level[3]);
            out << line;
        }
        out << '\n';
    }
    double total = 0.0;
    for (const auto& stage : s.stages) {
        std::snprintf(line, sizeof line, "  %-26s %8.2f s\n", stage.stage.c_str(), stage.seconds);
        out << line;
        total += stage.seconds;
    }
    std::snprintf(line, sizeof line, "  %-26s %8.2f s\npeak memory %.0f MiB\n", "total", total,
                  static_cast<double>(s.peak_memory_bytes) / (1024.0 * 1024.0));
    out << line;
    return out.str();
}

}  // namespace splat_lod::bake
