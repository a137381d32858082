#pragma once
// The LOD parts of report.md, from the scale sweep's means over the views:
//   - the verdict: `full` against `baseline` per scale (PSNR gain, speed-up of the splat pass),
//     checked against Yan et al.'s claims: ≥ 3 dB better at 16× and 64×, ≥ 5× cheaper
//     at 64×, and at 1× (where the reference is the baseline itself) a PSNR of at least 40 dB;
//   - matched Gaussian counts: per scale, `full` next to the comparison scenes (e.g. the levels of
//     an existing LOD chain) that draw about as many Gaussians.
#include <optional>
#include <string>
#include <vector>

#include "splat_lod/eval/criterion.h"
#include "splat_lod/eval/eval_run.h"

namespace splat_lod::eval {

struct LodVerdictRow {
    int scale = 1;
    std::optional<double> full_psnr;     // against the reference (dB)
    std::optional<double> psnr_gain_db;  // full − baseline; absent unless both are finite
    std::optional<double> speedup;       // baseline splat GPU ms / full splat GPU ms; absent without times
};

using LodCriterion = Criterion;  // value absent: the scale was not measured

struct LodVerdict {
    std::vector<LodVerdictRow> rows;  // one per scale of the sweep
    std::vector<LodCriterion> criteria;
};

// Present when the scale sweep measured both `baseline` and `full`.
std::optional<LodVerdict> lod_verdict(const EvalResults& results);
std::string lod_verdict_markdown(const LodVerdict& verdict);

struct MatchedEntry {
    std::string method;
    double drawn = 0.0;  // mean Gaussians drawn
    std::optional<double> psnr, ssim;
    double splat_gpu_ms = 0.0;
};

struct MatchedCounts {
    int scale = 1;
    MatchedEntry full;
    MatchedEntry nearest;                     // the comparison scene nearest in drawn count
    std::optional<MatchedEntry> next_larger;  // the one drawing the next larger count, if any
};

// One per scale when the scale sweep measured `full` and at least one comparison scene.
std::vector<MatchedCounts> matched_counts(const EvalResults& results);
std::string matched_counts_markdown(const std::vector<MatchedCounts>& matched);

}  // namespace splat_lod::eval
