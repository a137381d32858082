#include "splat_lod/eval/lod_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "splat_lod/eval/eval_report.h"

namespace splat_lod::eval {
namespace {

// Yan et al.'s claims for its full method against the baseline renderer.
constexpr double kMinGainDb = 3.0;     // at 16× and 64×
constexpr double kMinSpeedup = 5.0;    // at 64×
constexpr double kMinPsnrAt1x = 40.0;  // at 1×, against the reference (= baseline there)

bool measured(const EvalResults& results, const std::string& method) {
    return std::any_of(results.rows.begin(), results.rows.end(),
                       [&](const Measurement& row) { return row.sweep == Sweep::scale && row.method == method; });
}

const LodVerdictRow* row_at(const LodVerdict& verdict, int scale) {
    for (const auto& row : verdict.rows)
        if (row.scale == scale) return &row;
    return nullptr;
}

LodCriterion gain_criterion(const LodVerdict& verdict, int scale) {
    LodCriterion c;
    c.text = std::to_string(scale) + "\u00d7: full \u2212 baseline PSNR \u2265 +" + format_fixed(kMinGainDb, 0) + " dB";
    if (const LodVerdictRow* row = row_at(verdict, scale); row && row->psnr_gain_db) {
        c.value = row->psnr_gain_db;
        c.value_text = format_signed_db(*c.value);
        c.met = *c.value >= kMinGainDb;
    }
    return c;
}

LodCriterion speedup_criterion(const LodVerdict& verdict, int scale) {
    LodCriterion c;
    c.text =
        std::to_string(scale) + "\u00d7: speed-up of the splat pass \u2265 " + format_fixed(kMinSpeedup, 0) + "\u00d7";
    if (const LodVerdictRow* row = row_at(verdict, scale); row && row->speedup) {
        c.value = row->speedup;
        c.value_text = format_fixed(*c.value, 2) + "\u00d7";
        c.met = *c.value >= kMinSpeedup;
    }
    return c;
}

LodCriterion fidelity_criterion(const LodVerdict& verdict) {
    LodCriterion c;
    c.text = "1\u00d7: full PSNR against the reference (the baseline at 1\u00d7) \u2265 " +
             format_fixed(kMinPsnrAt1x, 0) + " dB";
    if (const LodVerdictRow* row = row_at(verdict, 1); row && row->full_psnr) {
        c.value = row->full_psnr;
        c.value_text = format_db(c.value) + " dB";
        c.met = *c.value >= kMinPsnrAt1x;
    }
    return c;
}

MatchedEntry entry(const EvalResults& results, const std::string& method, int scale) {
    const Summary s = summarize(results, Sweep::scale, method, scale);
    return {method, s.visible, s.psnr, s.ssim, s.splat_gpu_ms};
}

std::string entry_row(int scale, const MatchedEntry& e, const std::string& role) {
    return "| " + std::to_string(scale) + "\u00d7 | " + e.method + role + " | " + format_count(e.drawn) + " | " +
           format_db(e.psnr) + " | " + (e.ssim ? format_fixed(*e.ssim, 3) : "\u2013") + " | " +
           format_fixed(e.splat_gpu_ms, 2) + " |\n";
}

}  // namespace

std::optional<LodVerdict> lod_verdict(const EvalResults& results) {
    if (!measured(results, "baseline") || !measured(results, "full")) return std::nullopt;
    LodVerdict verdict;
    for (int k : results.options.scales) {
        const Summary base = summarize(results, Sweep::scale, "baseline", k);
        const Summary full = summarize(results, Sweep::scale, "full", k);
        LodVerdictRow row;
        row.scale = k;
        row.full_psnr = full.psnr;
        if (base.psnr && full.psnr && std::isfinite(*base.psnr) && std::isfinite(*full.psnr))
            row.psnr_gain_db = *full.psnr - *base.psnr;
        if (base.splat_gpu_ms > 0.0 && full.splat_gpu_ms > 0.0) row.speedup = base.splat_gpu_ms / full.splat_gpu_ms;
        verdict.rows.push_back(row);
    }
    verdict.criteria = {gain_criterion(verdict, 16), gain_criterion(verdict, 64), speedup_criterion(verdict, 64),
                        fidelity_criterion(verdict)};
    return verdict;
}

std::string lod_verdict_markdown(const LodVerdict& verdict) {
    std::ostringstream out;
    out << "#### LOD verdict: full against baseline\n\n"
           "| scale | full PSNR (dB) | full \u2212 baseline PSNR (dB) | speed-up (baseline / full splat GPU ms) |\n"
           "|---|---|---|---|\n";
    for (const auto& row : verdict.rows)
        out << "| " << row.scale << "\u00d7 | " << format_db(row.full_psnr) << " | "
            << (row.psnr_gain_db ? format_signed_db(*row.psnr_gain_db) : "\u2013") << " | "
            << (row.speedup ? format_fixed(*row.speedup, 2) + "\u00d7" : "\u2013") << " |\n";
    out << '\n';
    for (const auto& c : verdict.criteria) out << criterion_line(c);
    return out.str();
}

std::vector<MatchedCounts> matched_counts(const EvalResults& results) {
    const auto& o = results.options;
    std::vector<MatchedCounts> out;
    if (o.comparisons.empty() || !measured(results, "full")) return out;
    for (int k : o.scales) {
        MatchedCounts m;
        m.scale = k;
        m.full = entry(results, "full", k);
        std::vector<MatchedEntry> candidates;
        for (const auto& comparison : o.comparisons)
            if (measured(results, comparison.method)) candidates.push_back(entry(results, comparison.method, k));
        if (candidates.empty()) return {};
        const auto by_distance = [&](const MatchedEntry& a, const MatchedEntry& b) {
            return std::abs(a.drawn - m.full.drawn) < std::abs(b.drawn - m.full.drawn);
        };
        m.nearest = *std::min_element(candidates.begin(), candidates.end(), by_distance);
        for (const auto& c : candidates)
            if (c.drawn > m.nearest.drawn && (!m.next_larger || c.drawn < m.next_larger->drawn)) m.next_larger = c;
        out.push_back(m);
    }
    return out;
}

std::string matched_counts_markdown(const std::vector<MatchedCounts>& matched) {
    std::ostringstream out;
    out << "#### Matched Gaussian counts: full against the comparison scenes\n\n"
           "Per scale: `full`, the comparison scene whose mean count of Gaussians drawn is nearest to full's, and "
           "the one drawing the next larger count; all against the same reference.\n\n"
           "| scale | method | drawn | PSNR (dB) | SSIM | GPU splat ms |\n|---|---|---|---|---|---|\n";
    for (const auto& m : matched) {
        out << entry_row(m.scale, m.full, "");
        out << entry_row(m.scale, m.nearest, " (nearest)");
        if (m.next_larger) out << entry_row(m.scale, *m.next_larger, " (next larger)");
    }
    return out.str();
}

}  // namespace splat_lod::eval
