// The evaluation's report on hand-made measurements (no GL): the Gaussians drawn per level, the LOD
// verdict, the matched-count comparison, the CSV columns, the upscale table, verdict, crops and
// option checks, and reading an LOD chain's lod-meta.json.
#include <fstream>
#include <limits>
#include <sstream>

#include "engine/core/error.h"
#include "splat_lod/eval/eval_report.h"
#include "splat_lod/eval/lod_chain.h"
#include "splat_lod/eval/lod_report.h"
#include "splat_lod/eval/upscale_report.h"
#include "test_support.h"

namespace eval = splat_lod::eval;

namespace {

template <class F>
void expect_error(F&& f, std::initializer_list<std::string> parts) {
    try {
        f();
        ADD_FAILURE() << "no engine::Error thrown";
    } catch (const engine::Error& e) {
        for (const auto& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

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
    EXPECT_NE(csv.find(",considered,skipped,visible,drawn_l1,drawn_l2,drawn_l3,drawn_l4,tile_splat_pairs,"), std::string::npos)
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

// The upscale sweep on 512×384, two views: native and spline, bicubic, spline_plain at 2×, 3×, 4×.
struct UpscaleNumbers {
    double psnr = 40.0, wall_ms = 20.0, splat_ms = 15.0, upscale_ms = 2.0;
};

eval::Measurement upscale_row(const std::string& method, int factor, int view, const UpscaleNumbers& n) {
    eval::Measurement m;
    m.scene = "hand";
    m.sweep = eval::Sweep::upscale;
    m.view = view;
    m.view_name = "orbit " + std::to_string(view);
    m.method = method;
    m.factor = factor;
    m.width = 512;
    m.height = 384;
    m.psnr = n.psnr;
    m.ssim = n.psnr > 100.0 ? 1.0 : 0.9;
    m.wall_ms = n.wall_ms;
    m.gpu_ms["splat"] = n.splat_ms;
    if (factor > 1) m.gpu_ms["splat.upscale"] = n.upscale_ms;
    return m;
}

eval::EvalResults upscale_results() {
    eval::EvalResults r;
    r.options.scene_name = "hand";
    r.options.width = 512;
    r.options.height = 384;
    r.options.sweeps = {eval::Sweep::upscale};
    r.options.upscale_factors = {2, 3, 4};
    r.options.upscalers = eval::select_upscalers("spline,bicubic,spline_plain");
    r.views = 2;
    const double inf = std::numeric_limits<double>::infinity();
    for (int view = 0; view < 2; ++view) {
        const double d = view == 0 ? -0.5 : 0.5;  // cancels in the means
        r.rows.push_back(upscale_row("native", 1, view, {inf, 100.0, 90.0, 0.0}));
        r.rows.push_back(upscale_row("spline", 2, view, {46.0 + d, 40.0, 32.0, 4.0}));
        r.rows.push_back(upscale_row("bicubic", 2, view, {41.0 - d, 38.0, 30.0, 2.0}));
        r.rows.push_back(upscale_row("spline_plain", 2, view, {33.0, 40.0, 32.0, 4.0}));
        r.rows.push_back(upscale_row("spline", 3, view, {40.0, 25.0 + 10 * d, 20.0, 3.0}));
        r.rows.push_back(upscale_row("bicubic", 3, view, {38.0, 24.0, 19.0, 1.5}));
        r.rows.push_back(upscale_row("spline_plain", 3, view, {30.0, 25.0, 20.0, 3.0}));
        r.rows.push_back(upscale_row("spline", 4, view, {37.0, 20.0, 15.0, 2.5}));
        r.rows.push_back(upscale_row("bicubic", 4, view, {35.0, 19.0, 14.0, 1.0}));
        r.rows.push_back(upscale_row("spline_plain", 4, view, {28.0, 20.0, 15.0, 2.5}));
    }
    return r;
}

TEST(SplatEvalUpscale, TableHasRasterSizesTimesAndSpeedUps) {
    const auto entries = eval::upscale_entries(upscale_results());
    ASSERT_EQ(entries.size(), 1u + 3u * 3u);
    EXPECT_EQ(entries[0].upscaler, "native");
    EXPECT_DOUBLE_EQ(*entries[0].speedup_wall, 1.0);
    const auto& spline3 = entries[4];
    EXPECT_EQ(spline3.upscaler, "spline");
    EXPECT_EQ(spline3.factor, 3);
    EXPECT_EQ(spline3.source_width, 171) << "\u2308512/3\u2309";
    EXPECT_EQ(spline3.source_height, 128);
    EXPECT_DOUBLE_EQ(spline3.render_ms, 17.0) << "the splat pass without splat.upscale";
    EXPECT_DOUBLE_EQ(spline3.upscale_ms, 3.0);
    EXPECT_DOUBLE_EQ(*spline3.speedup_wall, 4.0);
    EXPECT_DOUBLE_EQ(*spline3.speedup_gpu, 4.5);
    EXPECT_TRUE(spline3.upscale_timed);

    const std::string table = eval::upscale_table_markdown(entries);
    EXPECT_NE(table.find("| factor | upscaler | raster size | PSNR (dB) | SSIM | render ms | upscale ms | frame ms |"),
              std::string::npos)
        << table;
    EXPECT_NE(table.find("| 1\u00d7 | native | 512\u00d7384 | \u221e | 1.0000 | 90.00 | \u2013 | 100.00 | 1.00\u00d7 | "
                         "1.00\u00d7 |"),
              std::string::npos)
        << table;
    EXPECT_NE(table.find("| 3\u00d7 | spline | 171\u00d7128 | 40.00 | 0.9000 | 17.00 | 3.00 | 25.00 | 4.00\u00d7 | "
                         "4.50\u00d7 |"),
              std::string::npos)
        << table;
}

TEST(SplatEvalUpscale, VerdictChecksTheTargets) {
    const auto verdict = eval::upscale_verdict(upscale_results());
    ASSERT_TRUE(verdict);
    ASSERT_EQ(verdict->rows.size(), 3u);
    EXPECT_DOUBLE_EQ(*verdict->rows[0].gain_over_bicubic_db, 5.0);
    EXPECT_DOUBLE_EQ(*verdict->rows[0].gain_over_plain_db, 13.0);
    EXPECT_DOUBLE_EQ(*verdict->rows[1].gain_over_bicubic_db, 2.0);
    EXPECT_DOUBLE_EQ(*verdict->rows[2].gain_over_bicubic_db, 2.0);
    ASSERT_EQ(verdict->criteria.size(), 5u);
    EXPECT_TRUE(verdict->criteria[0].met);   // 2×: +5 dB ≥ 3
    EXPECT_FALSE(verdict->criteria[1].met);  // 3×: +2 dB < 3
    EXPECT_FALSE(verdict->criteria[2].met);  // 4×: +2 dB
    EXPECT_TRUE(verdict->criteria[3].met);   // 3×: 40 dB ≥ 38
    EXPECT_TRUE(verdict->criteria[4].met);   // 3×: 4× ≥ 2.5×

    const std::string text = eval::upscale_verdict_markdown(*verdict);
    EXPECT_NE(text.find("| 3\u00d7 | 40.00 | 38.00 | +2.00 dB | +10.00 dB | 4.00\u00d7 | 4.50\u00d7 |"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("- \u2713 2\u00d7: spline \u2212 bicubic PSNR \u2265 +3 dB: +5.00 dB\n"), std::string::npos)
        << text;
    EXPECT_NE(text.find("- \u2717 3\u00d7: spline \u2212 bicubic PSNR \u2265 +3 dB: +2.00 dB\n"), std::string::npos)
        << text;
    EXPECT_NE(text.find("- \u2713 3\u00d7: spline PSNR against native \u2265 38 dB: 40.00 dB\n"), std::string::npos)
        << text;
    EXPECT_NE(text.find("- \u2713 3\u00d7: spline frame speed-up over native \u2265 2.5\u00d7 (a target at "
                        "1920\u00d71080; measured at 512\u00d7384): 4.00\u00d7\n"),
              std::string::npos)
        << text;

    eval::EvalResults hd = upscale_results();
    hd.options.width = 1920;
    hd.options.height = 1080;
    EXPECT_EQ(eval::upscale_verdict(hd)->criteria[4].text,
              "3\u00d7: spline frame speed-up over native \u2265 2.5\u00d7 (at 1920\u00d71080)");
}

TEST(SplatEvalUpscale, VerdictSaysWhatIsMissing) {
    eval::EvalResults no_bicubic = upscale_results();
    std::erase_if(no_bicubic.rows, [](const eval::Measurement& m) { return m.method == "bicubic"; });
    const auto verdict = eval::upscale_verdict(no_bicubic);
    ASSERT_TRUE(verdict);
    EXPECT_FALSE(verdict->criteria[0].value);
    EXPECT_TRUE(verdict->criteria[3].value);
    EXPECT_NE(eval::upscale_verdict_markdown(*verdict).find(
                  "- \u2013 2\u00d7: spline \u2212 bicubic PSNR \u2265 +3 dB: not measured"),
              std::string::npos);

    eval::EvalResults no_spline = upscale_results();
    std::erase_if(no_spline.rows, [](const eval::Measurement& m) { return m.method == "spline"; });
    EXPECT_FALSE(eval::upscale_verdict(no_spline));
    EXPECT_TRUE(eval::upscale_entries(eval::EvalResults{}).empty());
}

TEST(SplatEvalUpscale, ReportAndCsvCarryTheSweep) {
    const auto folder = engine::test::output_dir("splat_eval_report") / "upscale";
    eval::EvalResults r = upscale_results();
    eval::write_markdown_report(r, "test", folder / "report.md");
    std::string report = read_text(folder / "report.md");
    EXPECT_NE(report.find("### Upscale sweep"), std::string::npos) << report;
    EXPECT_NE(report.find("#### Upscale verdict: spline against bicubic and native"), std::string::npos);
    EXPECT_EQ(report.find("### Scale sweep"), std::string::npos);
    EXPECT_EQ(report.find("No `splat.upscale` GPU span"), std::string::npos);

    // A pass that ignored the render scale records no upscale span: the report says so.
    for (auto& m : r.rows)
        if (m.method == "bicubic" && m.factor == 4 && m.view == 1) m.gpu_ms.erase("splat.upscale");
    eval::write_markdown_report(r, "test", folder / "report.md");
    report = read_text(folder / "report.md");
    EXPECT_NE(report.find("**No `splat.upscale` GPU span was recorded** for 4\u00d7 bicubic:"), std::string::npos)
        << report;
    EXPECT_NE(report.find("| 4\u00d7 | bicubic | 128\u00d796 | 35.00 | 0.9000 | 13.50 | \u2013 |"), std::string::npos)
        << report;

    eval::write_csv(r, folder / "measurements.csv");
    const std::string csv = read_text(folder / "measurements.csv");
    EXPECT_NE(csv.find(",wall_ms,gpu_splat_ms,gpu_splat.upscale_ms,"), std::string::npos) << csv;
    EXPECT_NE(csv.find("hand,upscale,0,\"orbit 0\",native,1,512,384,inf,1.000000,100.000,90.000,,"), std::string::npos)
        << csv;
    EXPECT_NE(csv.find("hand,upscale,1,\"orbit 1\",spline,3,512,384,40.0000,0.900000,30.000,20.000,3.000,"),
              std::string::npos)
        << csv;
}

// A black image with a noisy square: the detail window is on it.
engine::Image noise_square(int width, int height, int x0, int y0, int side) {
    engine::Image image{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width * height) * 4, 0)};
    for (int y = y0; y < y0 + side; ++y)
        for (int x = x0; x < x0 + side; ++x)
            std::fill_n(image.pixel(x, y), 3, static_cast<std::uint8_t>((x * 7 + y * 13) % 5 * 60));
    return image;
}

TEST(SplatEvalUpscale, CropsShowTheMostDetailedWindow) {
    const engine::Image image = noise_square(320, 200, 200, 100, 40);
    const eval::CropWindow w = eval::detail_window(image, 96);
    EXPECT_EQ(w.width, 96);
    EXPECT_EQ(w.height, 96);
    EXPECT_LE(w.x, 200);
    EXPECT_GE(w.x + w.width, 240);
    EXPECT_LE(w.y, 100);
    EXPECT_GE(w.y + w.height, 140);
    const eval::CropWindow small = eval::detail_window(noise_square(50, 30, 0, 0, 10), 96);
    EXPECT_EQ(small.width, 50) << "clipped to the image";
    EXPECT_EQ(small.height, 30);

    eval::EvalResults r = upscale_results();
    EXPECT_EQ(eval::upscale_crop_columns(r.options),
              (std::vector<std::string>{"native", "bicubic", "spline", "spline_plain"}));
    EXPECT_EQ(eval::upscale_crop_factors(r.options), (std::vector<int>{3, 4}));
    r.options.upscale_factors = {2, 8};
    EXPECT_EQ(eval::upscale_crop_factors(r.options), (std::vector<int>{2}));
    r.options.upscale_factors = {2, 3, 4};
    r.upscale_tiles.push_back({"native", 1, image});
    for (const char* method : {"spline", "bicubic", "spline_plain"})
        for (int f : {3, 4}) r.upscale_tiles.push_back({method, f, image});
    const auto folder = engine::test::output_dir("splat_eval_report") / "upscale";
    eval::write_upscale_crops(r, folder / "upscale_crops.png");
    const engine::Image crops = engine::read_png(folder / "upscale_crops.png");
    EXPECT_EQ(crops.width, 40 + 4 * (288 + 2));
    EXPECT_EQ(crops.height, 2 * (16 + 288 + 2));
    // The native crop (first column, first row) shows the square magnified by 3.
    ASSERT_GT(image.pixel(211, 110)[0], 0);
    for (int dy = 0; dy < 3; ++dy)
        for (int dx = 0; dx < 3; ++dx)
            EXPECT_EQ(crops.pixel(40 + (211 - w.x) * 3 + dx, 16 + (110 - w.y) * 3 + dy)[0], image.pixel(211, 110)[0]);
}

TEST(SplatEvalUpscale, BadOptionsFailBeforeRendering) {
    eval::EvalOptions o;
    o.sweeps = {eval::Sweep::upscale};
    o.width = 96;
    o.height = 64;
    o.upscale_factors = {2, 3, 4, 8};
    EXPECT_NO_THROW(eval::validate_options(o)) << "no --methods needed for the upscale sweep alone";
    o.upscale_factors = {2, 1};
    expect_error([&] { eval::validate_options(o); }, {"--upscale-factors", "factor 1", "\u2265 2"});
    o.upscale_factors = {3, 3};
    expect_error([&] { eval::validate_options(o); }, {"--upscale-factors", "factor 3", "twice"});
    o.upscale_factors = {16};
    expect_error([&] { eval::validate_options(o); },
                 {"--upscale-factors", "factor 16", "too large for 96\u00d764", "6\u00d74 pixels"});
    o.upscale_factors = {2};
    o.upscale_mode = "fancy";
    expect_error([&] { eval::validate_options(o); }, {"--upscale-mode", "\"fancy\"", "baseline"});
    o.upscale_mode = "full";
    o.upscalers.clear();
    expect_error([&] { eval::validate_options(o); }, {"--upscalers", "no upscaler"});
    o.sweeps = {eval::Sweep::scale};
    o.scales = {1};
    o.methods = eval::select_methods("baseline");
    EXPECT_NO_THROW(eval::validate_options(o)) << "upscale options are checked only for the upscale sweep";

    expect_error([] { eval::parse_int_list("2,0", "--upscale-factors"); }, {"--upscale-factors", "\"0\""});
    expect_error([] { eval::select_upscalers("spline,nearest"); }, {"--upscalers", "\"nearest\"", "lanczos3"});
    expect_error([] { eval::select_upscalers("spline,spline"); }, {"--upscalers", "twice"});
    const auto all = eval::select_upscalers("spline_plain,lanczos3");
    ASSERT_EQ(all.size(), 2u);
    EXPECT_FALSE(all[0].scaled_dilation);
    EXPECT_EQ(all[0].upscaler, plugin_msgs::Upscaler::spline);
    EXPECT_EQ(all[1].upscaler, plugin_msgs::Upscaler::lanczos3);
    EXPECT_TRUE(all[1].scaled_dilation);
}

// A chain folder with empty level files (reading the chain does not load them).
std::filesystem::path chain_folder(const std::string& name) {
    const auto folder = engine::test::output_dir("splat_eval_report") / name;
    std::filesystem::create_directories(folder);
    for (const char* level : {"0_0", "1_0", "2_0"}) {
        std::filesystem::create_directories(folder / level);
        std::ofstream(folder / level / "meta.json") << "{}";
    }
    return folder;
}

std::filesystem::path write_meta(const std::filesystem::path& folder, const std::string& text) {
    std::ofstream(folder / "lod-meta.json") << text;
    return folder / "lod-meta.json";
}

// PlayCanvas's layout: the file list is not in level order, two leaves share each level's file.
const char* kChain = R"({"lodLevels": 3, "filenames": ["0_0/meta.json", "2_0/meta.json", "1_0/meta.json"],
  "tree": {"children": [
    {"lods": {"0": {"file": 0, "offset": 0, "count": 600}, "1": {"file": 2, "offset": 0, "count": 300},
              "2": {"file": 1, "offset": 0, "count": 60}}},
    {"children": [{"lods": {"0": {"file": 0, "offset": 600, "count": 400}, "1": {"file": 2, "offset": 300, "count": 200},
                            "2": {"file": 1, "offset": 60, "count": 40}}}]}]}})";

TEST(SplatEvalChain, ReadsLevelFilesThroughTheTree) {
    const auto folder = chain_folder("good");
    const eval::LodChain chain = eval::read_lod_chain(write_meta(folder, kChain));
    ASSERT_EQ(chain.levels.size(), 3u);
    EXPECT_EQ(chain.levels[0].file, folder / "0_0/meta.json");
    EXPECT_EQ(chain.levels[1].file, folder / "1_0/meta.json");
    EXPECT_EQ(chain.levels[2].file, folder / "2_0/meta.json");
    EXPECT_EQ(chain.levels[0].gaussians, 1000u);
    EXPECT_EQ(chain.levels[1].gaussians, 500u);
    EXPECT_EQ(chain.levels[2].gaussians, 100u);
    EXPECT_EQ(chain.levels[2].level, 2);
    EXPECT_EQ(eval::chain_method_name(2), "chain_L2");
    const auto comparisons = eval::chain_comparisons(chain, folder / "0_0/meta.json", nullptr);
    ASSERT_EQ(comparisons.size(), 3u);
    EXPECT_EQ(comparisons[1].method, "chain_L1");
    EXPECT_NE(comparisons[1].description.find("1_0/meta.json, 500 Gaussians"), std::string::npos)
        << comparisons[1].description;
}

TEST(SplatEvalChain, BadFilesNameFileAndProblem) {
    const auto folder = chain_folder("bad");
    expect_error([&] { eval::read_lod_chain(folder / "absent.json"); }, {"absent.json"});
    expect_error([&] { eval::read_lod_chain(write_meta(folder, "{\"filenames\": [")); },
                 {"lod-meta.json", "not valid JSON"});
    expect_error([&] { eval::read_lod_chain(write_meta(folder, "[]")); }, {"lod-meta.json", "object"});

    std::string no_filenames = kChain;
    no_filenames.replace(no_filenames.find("\"filenames\""), 11, "\"files\"");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, no_filenames)); },
                 {"lod-meta.json", "missing \"filenames\""});

    std::string bad_index = kChain;
    bad_index.replace(bad_index.find("\"file\": 1, \"offset\": 60"), 9, "\"file\": 7");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, bad_index)); },
                 {"lod-meta.json", "tree.children[1].children[0].lods[\"2\"]", "file index 7", "3 entries"});

    std::string split = kChain;
    split.replace(split.find("\"file\": 2, \"offset\": 300"), 9, "\"file\": 1");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, split)); },
                 {"lod-meta.json", "level 1 is split over files \"1_0/meta.json\" and \"2_0/meta.json\""});

    std::string beyond = kChain;
    beyond.replace(beyond.find("\"2\": {\"file\": 1, \"offset\": 60"), 6, "\"5\": {");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, beyond)); },
                 {"lod-meta.json", "level 5", "\"lodLevels\""});
    const char* missing_level = R"({"filenames": ["0_0/meta.json"], "tree": {"children": [
        {"lods": {"0": {"file": 0}, "1": {"file": 0}}}, {"lods": {"0": {"file": 0}}}]}})";
    expect_error([&] { eval::read_lod_chain(write_meta(folder, missing_level)); },
                 {"lod-meta.json", "level 1 is missing from tree.children[1]"});

    std::string no_tree = kChain;
    no_tree.replace(no_tree.find("\"tree\""), 6, "\"bush\"");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, no_tree)); }, {"lod-meta.json", "missing \"tree\""});

    std::filesystem::remove(folder / "2_0/meta.json");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, kChain)); },
                 {"lod-meta.json", "level 2", "2_0/meta.json", "does not exist"});
}

}  // namespace
