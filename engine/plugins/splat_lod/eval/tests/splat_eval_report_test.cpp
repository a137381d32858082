// The evaluation's report on hand-made measurements (no GL): the Gaussians drawn per level, the LOD
// verdict, the matched-count comparison, the CSV columns and the contact sheet's rows and option
// checks. The upscale sweep: splat_eval_report_test_upscale.cpp; LOD chains:
// splat_eval_report_test_chain.cpp.
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "splat_eval_report_test_helpers.h"
#include "splat_lod/eval/eval_method.h"
#include "splat_lod/eval/eval_report.h"
#include "splat_lod/eval/eval_run.h"
#include "splat_lod/eval/lod_chain.h"
#include "splat_lod/eval/lod_report.h"
#include "test_support.h"

namespace eval = splat_lod::eval;
using splat_eval_report_test::expect_error;
using splat_eval_report_test::read_text;

namespace {

struct Numbers {
    double psnr = 30.0, ssim = 0.9, gpu_ms = 10.0;
    std::array<std::uint64_t, 4> per_level{0, 0, 0, 0};
};

eval::Measurement row(const std::string& method, int scale, int view, const Numbers& n) {
    eval::Measurement m;
    m.scene = "hand";
    m.sweep = eval::Sweep::scale;
    m.view = view;
    m.view_name = "orbit " + std::to_string(view);
    m.method = method;
    m.factor = scale;
    m.width = 64 / scale;
    m.height = 64 / scale;
    m.psnr = n.psnr;
    m.ssim = n.ssim;
    m.wall_ms = n.gpu_ms + 1.0;
    m.gpu_ms["splat"] = n.gpu_ms;
    m.statistics.considered = 200000;
    m.statistics.per_level = n.per_level;
    for (auto count : n.per_level) m.statistics.visible += count;
    return m;
}

// Two views, baseline and full at 1×, 16× and 64×, with numbers whose means are easy to check.
eval::EvalResults lod_results() {
    eval::EvalResults r;
    r.options.scene_name = "hand";
    r.options.width = 64;
    r.options.height = 64;
    r.options.methods = eval::select_methods("baseline,full");
    r.options.scales = {1, 16, 64};
    r.views = 2;
    const double inf = std::numeric_limits<double>::infinity();
    for (int view = 0; view < 2; ++view) {
        const double d = view == 0 ? -0.5 : 0.5;  // cancels in the means over the two views
        r.rows.push_back(row("baseline", 1, view, {inf, 1.0, 100.0, {150000, 0, 0, 0}}));
        r.rows.push_back(row("baseline", 16, view, {20.0 + d, 0.5, 50.0 + 10 * d, {150000, 0, 0, 0}}));
        r.rows.push_back(row("baseline", 64, view, {15.0 + d, 0.2, 60.0, {150000, 0, 0, 0}}));
        r.rows.push_back(row("full", 1, view, {45.0 + d, 0.99, 80.0, {149000, 1000, 0, 0}}));
        r.rows.push_back(
            row("full", 16, view,
                {24.5 - d, 0.7, 10.0, {120000 + static_cast<std::uint64_t>(600 * (d + 0.5)), 2100, 50, 0}}));
        r.rows.push_back(row("full", 64, view, {17.0, 0.4, 10.0, {900, 2000, 3000, 1234567}}));
    }
    return r;
}

TEST(SplatEvalReport, ScaleTablesShowGaussiansDrawnPerLevel) {
    const auto folder = engine::test::output_dir("splat_eval_report");
    eval::write_markdown_report(lod_results(), "test", folder / "report.md");
    const std::string report = read_text(folder / "report.md");
    // Means over the two views: L1 = 120300 at 16×.
    EXPECT_NE(report.find("| full | 149.0k/1.0k/0/0 | 120.3k/2.1k/50/0 | 900/2.0k/3.0k/1.23M |"), std::string::npos)
        << report;
    EXPECT_NE(report.find("| baseline | 150.0k/0/0/0 | 150.0k/0/0/0 | 150.0k/0/0/0 |"), std::string::npos) << report;
    EXPECT_NE(report.find("| drawn L1/L2/L3/L4 |"), std::string::npos);
    EXPECT_NE(report.find("| full | 16\u00d7 | 4\u00d74 | 11.00 | 10.00 | 200000 | 122450 | 120.3k/2.1k/50/0 |"),
              std::string::npos)
        << report;
    EXPECT_NE(report.find("| full | 45.00 / 0.990 / 80.00 | 24.50 / 0.700 / 10.00 | 17.00 / 0.400 / 10.00 |"),
              std::string::npos)
        << report;

    eval::write_csv(lod_results(), folder / "measurements.csv");
    const std::string csv = read_text(folder / "measurements.csv");
    EXPECT_NE(csv.find(",considered,skipped,visible,drawn_l1,drawn_l2,drawn_l3,drawn_l4,tile_splat_pairs,"),
              std::string::npos)
        << csv;
    EXPECT_NE(csv.find(",200000,0,1240467,900,2000,3000,1234567,0,0\n"), std::string::npos) << csv;
}

TEST(SplatEvalReport, CountsAreShortAndReadable) {
    EXPECT_EQ(eval::format_count(0.0), "0");
    EXPECT_EQ(eval::format_count(999.4), "999");
    EXPECT_EQ(eval::format_count(999.6), "1.0k");
    EXPECT_EQ(eval::format_count(120345.0), "120.3k");
    EXPECT_EQ(eval::format_count(1234567.0), "1.23M");
    EXPECT_EQ(eval::format_levels({120345.0, 2100.0, 0.0, 0.0}), "120.3k/2.1k/0/0");
}

TEST(SplatEvalReport, LodVerdictComputesDifferencesAndRatios) {
    const auto verdict = eval::lod_verdict(lod_results());
    ASSERT_TRUE(verdict);
    ASSERT_EQ(verdict->rows.size(), 3u);
    const auto& at1 = verdict->rows[0];
    EXPECT_EQ(at1.scale, 1);
    EXPECT_DOUBLE_EQ(*at1.full_psnr, 45.0);
    EXPECT_FALSE(at1.psnr_gain_db) << "the baseline is the reference at 1x: no finite difference";
    EXPECT_DOUBLE_EQ(*at1.speedup, 100.0 / 80.0);
    EXPECT_DOUBLE_EQ(*verdict->rows[1].psnr_gain_db, 4.5);
    EXPECT_DOUBLE_EQ(*verdict->rows[1].speedup, 5.0);
    EXPECT_DOUBLE_EQ(*verdict->rows[2].psnr_gain_db, 2.0);
    EXPECT_DOUBLE_EQ(*verdict->rows[2].speedup, 6.0);

    ASSERT_EQ(verdict->criteria.size(), 4u);
    EXPECT_TRUE(verdict->criteria[0].met);   // 16×: +4.5 dB ≥ 3
    EXPECT_FALSE(verdict->criteria[1].met);  // 64×: +2 dB < 3
    EXPECT_TRUE(verdict->criteria[2].met);   // 64×: 6× ≥ 5×
    EXPECT_TRUE(verdict->criteria[3].met);   // 1×: 45 dB ≥ 40

    const std::string text = eval::lod_verdict_markdown(*verdict);
    EXPECT_NE(text.find("| 16\u00d7 | 24.50 | +4.50 dB | 5.00\u00d7 |"), std::string::npos) << text;
    EXPECT_NE(text.find("| 1\u00d7 | 45.00 | \u2013 | 1.25\u00d7 |"), std::string::npos) << text;
    EXPECT_NE(text.find("\u2713 16\u00d7: full \u2212 baseline PSNR \u2265 +3 dB: +4.50 dB"), std::string::npos)
        << text;
    EXPECT_NE(text.find("\u2717 64\u00d7: full \u2212 baseline PSNR \u2265 +3 dB: +2.00 dB"), std::string::npos)
        << text;
    EXPECT_NE(text.find("\u2713 64\u00d7: speed-up of the splat pass \u2265 5\u00d7: 6.00\u00d7"), std::string::npos)
        << text;
    EXPECT_NE(text.find("\u2713 1\u00d7: full PSNR"), std::string::npos) << text;
}

TEST(SplatEvalReport, LodVerdictOnlyWithBothMethodsAndSaysWhatIsMissing) {
    eval::EvalResults only_baseline = lod_results();
    std::erase_if(only_baseline.rows, [](const eval::Measurement& m) { return m.method == "full"; });
    EXPECT_FALSE(eval::lod_verdict(only_baseline));
    const auto folder = engine::test::output_dir("splat_eval_report");
    eval::write_markdown_report(only_baseline, "test", folder / "report.md");
    EXPECT_EQ(read_text(folder / "report.md").find("LOD verdict"), std::string::npos);

    eval::EvalResults no_64 = lod_results();
    no_64.options.scales = {1, 16};
    std::erase_if(no_64.rows, [](const eval::Measurement& m) { return m.factor == 64; });
    const auto verdict = eval::lod_verdict(no_64);
    ASSERT_TRUE(verdict);
    EXPECT_FALSE(verdict->criteria[1].value);
    EXPECT_NE(eval::lod_verdict_markdown(*verdict).find(
                  "\u2013 64\u00d7: speed-up of the splat pass \u2265 5\u00d7: not measured"),
              std::string::npos);
}

TEST(SplatEvalReport, MatchedCountsPickNearestAndNextLargerChainLevel) {
    eval::EvalResults r = lod_results();
    for (int level = 0; level < 3; ++level)
        r.options.comparisons.push_back({eval::chain_method_name(level), "level", {}});
    // Chain levels draw 150k, 20k and 5k Gaussians at every scale and view.
    const std::uint64_t drawn[3] = {150000, 20000, 5000};
    for (int view = 0; view < 2; ++view)
        for (int level = 0; level < 3; ++level)
            for (int k : {1, 16, 64})
                r.rows.push_back(row(eval::chain_method_name(level), k, view,
                                     {18.0 + level, 0.3, 40.0 - 10.0 * level, {drawn[level], 0, 0, 0}}));
    const auto matched = eval::matched_counts(r);
    ASSERT_EQ(matched.size(), 3u);
    // 1×: full draws 150k → level 0 is nearest, and no level draws more.
    EXPECT_EQ(matched[0].nearest.method, "chain_L0");
    EXPECT_FALSE(matched[0].next_larger);
    // 16×: full draws 122,450 → level 0 (150k) is nearer than level 1 (20k).
    EXPECT_EQ(matched[1].nearest.method, "chain_L0");
    // 64×: full draws 1,240,467 (its level-4 count is deliberately huge) → level 0 again.
    EXPECT_NEAR(matched[2].full.drawn, 1240467.0, 1e-6);
    EXPECT_EQ(matched[2].nearest.method, "chain_L0");

    // Move full's 16× count between levels 1 and 2: 6k is nearest to 5k (level 2), next larger is level 1.
    for (auto& m : r.rows)
        if (m.method == "full" && m.factor == 16) m.statistics.visible = 6000;
    const auto moved = eval::matched_counts(r);
    EXPECT_EQ(moved[1].full.drawn, 6000.0);
    EXPECT_EQ(moved[1].nearest.method, "chain_L2");
    ASSERT_TRUE(moved[1].next_larger);
    EXPECT_EQ(moved[1].next_larger->method, "chain_L1");
    EXPECT_DOUBLE_EQ(*moved[1].next_larger->psnr, 19.0);
    const std::string text = eval::matched_counts_markdown(moved);
    EXPECT_NE(text.find("| 16\u00d7 | full | 6.0k | 24.50 | 0.700 | 10.00 |"), std::string::npos) << text;
    EXPECT_NE(text.find("| 16\u00d7 | chain_L2 (nearest) | 5.0k | 20.00 | 0.300 | 20.00 |"), std::string::npos) << text;
    EXPECT_NE(text.find("| 16\u00d7 | chain_L1 (next larger) | 20.0k | 19.00 | 0.300 | 30.00 |"), std::string::npos)
        << text;

    const auto folder = engine::test::output_dir("splat_eval_report");
    eval::write_markdown_report(r, "test", folder / "report.md");
    const std::string report = read_text(folder / "report.md");
    EXPECT_NE(report.find("Matched Gaussian counts"), std::string::npos);
    EXPECT_NE(report.find("| chain_L2 | 5.0k/0/0/0 |"), std::string::npos) << "comparison scenes join the tables";
    EXPECT_NE(report.find("- `chain_L1`: level"), std::string::npos);

    r.options.comparisons.clear();
    EXPECT_TRUE(eval::matched_counts(r).empty());
}

TEST(SplatEvalReport, ContactSheetRowsAndTheirChecks) {
    eval::EvalOptions o;
    o.methods = eval::select_methods("baseline,full");
    EXPECT_EQ(eval::contact_sheet_rows(o), (std::vector<std::string>{"reference", "baseline", "full"}));
    o.comparisons.push_back({"chain_L0", "", {}});
    o.sheet_methods = {"full", "chain_L0"};
    EXPECT_EQ(eval::contact_sheet_rows(o), (std::vector<std::string>{"reference", "full", "chain_L0"}));
    EXPECT_NO_THROW(eval::validate_options(o));
    o.sheet_methods = {"full", "insert_large"};
    expect_error([&] { eval::validate_options(o); }, {"--sheet-methods", "\"insert_large\"", "chain_L0"});
    o.sheet_methods.clear();
    o.sweeps = {eval::Sweep::distance};
    expect_error([&] { eval::validate_options(o); }, {"--chain", "scale sweep"});
    o.sweeps = {eval::Sweep::scale};
    o.comparisons.push_back({"full", "", {}});
    expect_error([&] { eval::validate_options(o); }, {"\"full\""});
    expect_error([] { eval::parse_name_list("full,,baseline", "--sheet-methods"); }, {"--sheet-methods", "empty"});
    expect_error([] { eval::parse_name_list("full,full", "--sheet-methods"); }, {"--sheet-methods", "twice"});
}

}  // namespace
