// The evaluation's upscale sweep on hand-made measurements (no GL): the table of raster sizes, times
// and speed-ups, the verdict against its targets, the report and CSV, the detail crops and the checks
// of the upscale options.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/render/image.h"
#include "splat_eval_report_test_helpers.h"
#include "splat_lod/eval/eval_method.h"
#include "splat_lod/eval/eval_report.h"
#include "splat_lod/eval/eval_run.h"
#include "splat_lod/eval/upscale_report.h"
#include "splat_lod/msgs/lod_settings.h"
#include "test_support.h"

namespace eval = splat_lod::eval;
using splat_eval_report_test::expect_error;
using splat_eval_report_test::read_text;

namespace {

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

}  // namespace
