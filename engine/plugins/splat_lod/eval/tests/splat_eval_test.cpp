// splat_eval end to end on a tiny synthetic cloud: the scale and distance sweeps, every output file;
// the comparison with a tiny two-level LOD chain written as INRIA PLY files and a lod-meta.json; and
// the upscale sweep (every upscaler against the native render, the crops picture).
#include <cmath>
#include <fstream>
#include <sstream>

#include "engine/core/error.h"
#include "gpu_fixture.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/eval/eval_report.h"
#include "splat_lod/eval/eval_run.h"
#include "splat_lod/eval/eval_scene.h"
#include "splat_lod/eval/frame_measurer.h"
#include "splat_lod/eval/lod_chain.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace eval = splat_lod::eval;

namespace {

std::vector<std::string> read_lines(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::shared_ptr<const splat_lod::SplatCloud> small_cloud() {
    std::vector<engine::test::GaussianSpec> specs;
    for (int i = 0; i < 27; ++i) {
        engine::test::GaussianSpec s;
        s.position = glm::vec3(static_cast<float>(i % 3) - 1.0f, static_cast<float>(i / 3 % 3) - 1.0f,
                               static_cast<float>(i / 9) - 1.0f) *
                     0.6f;
        s.log_scale = glm::vec3(-1.6f);
        s.color = glm::vec3(0.2f + 0.3f * static_cast<float>(i % 3), 0.3f, 0.9f - 0.3f * static_cast<float>(i / 9));
        specs.push_back(s);
    }
    return std::make_shared<const splat_lod::SplatCloud>(engine::test::make_cloud(specs));
}

// The same cube drawn by its 8 corners, larger: a coarse level of small_cloud().
std::shared_ptr<const splat_lod::SplatCloud> coarse_cloud() {
    std::vector<engine::test::GaussianSpec> specs;
    for (int i = 0; i < 8; ++i) {
        engine::test::GaussianSpec s;
        s.position = glm::vec3(i % 2 ? 0.6f : -0.6f, i / 2 % 2 ? 0.6f : -0.6f, i / 4 ? 0.6f : -0.6f);
        s.log_scale = glm::vec3(-1.0f);
        s.color = glm::vec3(0.5f, 0.3f, 0.6f);
        specs.push_back(s);
    }
    return std::make_shared<const splat_lod::SplatCloud>(engine::test::make_cloud(specs));
}

// Level 0 is fine/scene.ply, level 1 coarse/scene.ply; the file list is not in level order, as in
// PlayCanvas's chains.
void write_chain(const std::filesystem::path& folder) {
    splat_lod::write_inria_ply(folder / "fine" / "scene.ply", *small_cloud());
    splat_lod::write_inria_ply(folder / "coarse" / "scene.ply", *coarse_cloud());
    std::ofstream(folder / "lod-meta.json") << R"({"lodLevels": 2, "filenames": ["coarse/scene.ply", "fine/scene.ply"],
        "tree": {"children": [{"lods": {"0": {"file": 1, "offset": 0, "count": 27}, "1": {"file": 0, "offset": 0, "count": 8}}}]}})";
}

class SplatEvalTest : public engine::test::GpuTest {};

TEST_F(SplatEvalTest, WholeRunWritesMeasurementsReportPlotsAndContactSheet) {
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    eval::EvalScene scene = eval::make_splat_scene(small_cloud());
    const auto poses = eval::orbit_poses(scene.extent, {0, 1, 0}, 1);

    eval::EvalOptions options;
    options.scene_name = "tiny";
    options.width = 64;
    options.height = 48;
    options.frames = 2;
    options.warmup = 1;
    options.methods = eval::select_methods("baseline,baseline_mip");
    options.sweeps = {eval::Sweep::scale, eval::Sweep::distance};
    options.scales = {1, 2, 4, 16};
    options.distances = {1, 2, 8};
    options.max_reference_side = 128;  // errors for d = 1, 2 only
    int progress_lines = 0;
    options.progress = [&](const std::string& line) {
        ++progress_lines;
        EXPECT_NE(line.find("tiny view 0"), std::string::npos) << line;
    };
    eval::FrameMeasurer measurer(engine, *scene.scene);
    const eval::EvalResults results = eval::run_evaluation(measurer, poses, options);
    EXPECT_EQ(progress_lines, 2 * 4 + 2 * 3);
    ASSERT_EQ(results.rows.size(), 14u);
    EXPECT_EQ(results.max_reference_distance, 2);

    for (const auto& row : results.rows) {
        EXPECT_EQ(row.statistics.considered, 27u);
        EXPECT_GT(row.wall_ms, 0.0);
        EXPECT_TRUE(row.gpu_ms.count("splat")) << "no GPU time for the splat pass";
        EXPECT_EQ(row.width, row.sweep == eval::Sweep::scale ? 64 / row.factor : 64);
        EXPECT_EQ(row.psnr.has_value(), row.sweep == eval::Sweep::scale || row.factor <= 2);
    }
    const auto& first = results.rows.front();
    ASSERT_EQ(first.method, "baseline");
    ASSERT_EQ(first.factor, 1);
    // The reference is the same model and renderer drawn from full floats: only the compact storage's
    // error is left (docs/gpu_storage.md wants at least 45 dB).
    EXPECT_GT(*first.psnr, 50.0) << "the baseline at scale 1 against its reference";
    EXPECT_LT(*first.psnr, 200.0) << "the reference is drawn from full floats, the method compact";
    EXPECT_NEAR(*first.ssim, 1.0, 1e-3);
    EXPECT_GT(first.statistics.visible, 0u);

    const auto folder = engine::test::output_dir("splat_eval") / "tiny";
    std::filesystem::remove_all(folder);
    eval::write_outputs(results, "test", folder);
    const auto csv = read_lines(folder / "measurements.csv");
    ASSERT_EQ(csv.size(), 15u);
    EXPECT_EQ(csv[0].rfind("scene,sweep,view,view_name,method,factor,width,height,psnr_db,ssim,wall_ms", 0), 0u);
    EXPECT_EQ(csv[1].rfind("tiny,scale,0,\"orbit 0\",baseline,1,64,48,", 0), 0u) << csv[1];
    for (const char* file :
         {"report.md", "contact_sheet.png", "time_vs_error.png", "time_vs_distance.png", "gaussians_vs_distance.png"})
        EXPECT_TRUE(std::filesystem::exists(folder / file)) << file;
    const engine::Image sheet = engine::read_png(folder / "contact_sheet.png");
    EXPECT_EQ(sheet.width, 96 + 4 * (16 + 2));
    std::ifstream report(folder / "report.md");
    std::stringstream text;
    text << report.rdbuf();
    EXPECT_NE(text.str().find("| baseline_mip |"), std::string::npos);
}

TEST_F(SplatEvalTest, ChainLevelsAreMeasuredAgainstTheMainScenesReference) {
    const auto folder = engine::test::output_dir("splat_eval") / "chain";
    std::filesystem::remove_all(folder);
    write_chain(folder);
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    const auto main_file = folder / "fine" / "scene.ply";
    eval::EvalScene scene = eval::load_splat_file_scene(main_file);
    const auto poses = eval::orbit_poses(scene.extent, {0, 1, 0}, 1);

    eval::EvalOptions options;
    options.scene_name = "chain";
    options.width = 64;
    options.height = 48;
    options.frames = 1;
    options.warmup = 0;
    options.methods = eval::select_methods("baseline,full");
    options.scales = {1, 4};
    options.sheet_methods = {"full", "chain_L1"};
    options.comparisons = eval::chain_comparisons(eval::read_lod_chain(folder / "lod-meta.json"), main_file,
                                                  scene.scene->components<splat_lod::SplatComponent>().front()->cloud);
    int progress_lines = 0;
    options.progress = [&](const std::string&) { ++progress_lines; };
    eval::FrameMeasurer measurer(engine, *scene.scene);
    const eval::EvalResults results = eval::run_evaluation(measurer, poses, options);
    EXPECT_EQ(progress_lines, 4 * 2);
    ASSERT_EQ(results.rows.size(), 8u);

    const auto find = [&](const std::string& method, int scale) -> const eval::Measurement& {
        for (const auto& row : results.rows)
            if (row.method == method && row.factor == scale) return row;
        throw std::runtime_error("no row for " + method);
    };
    EXPECT_EQ(find("chain_L0", 1).statistics.considered, 27u);
    EXPECT_EQ(find("chain_L1", 4).statistics.considered, 8u);
    EXPECT_EQ(find("chain_L1", 4).width, 16);
    EXPECT_GT(*find("chain_L0", 1).psnr, 50.0) << "level 0 is the main scene: its reference up to the storage";
    EXPECT_NEAR(*find("chain_L0", 4).psnr, *find("baseline", 4).psnr, 0.01);
    EXPECT_LT(*find("chain_L1", 1).psnr, 40.0) << "the coarse level is a different model";
    EXPECT_GT(*find("chain_L1", 1).psnr, 5.0);

    // The level picture: scales 1, 4 and 16 fit 64×48; without baked levels everything is level 1 (grey).
    ASSERT_EQ(results.level_tiles.size(), 3u);
    const engine::Image& levels = results.level_tiles.front().image;
    int lit = 0;
    for (int y = 0; y < levels.height; ++y)
        for (int x = 0; x < levels.width; ++x) {
            const std::uint8_t* p = levels.pixel(x, y);
            lit += p[0] > 0;
            EXPECT_LE(std::abs(p[0] - p[1]) + std::abs(p[1] - p[2]), 2) << "not grey at " << x << "," << y;
        }
    EXPECT_GT(lit, 0);

    eval::write_outputs(results, "test", folder / "out");
    const auto csv = read_lines(folder / "out" / "measurements.csv");
    ASSERT_EQ(csv.size(), 9u);
    EXPECT_NE(csv[0].find(",drawn_l1,drawn_l2,drawn_l3,drawn_l4,"), std::string::npos);
    const engine::Image sheet = engine::read_png(folder / "out" / "contact_sheet.png");
    EXPECT_EQ(sheet.height, 16 + 3 * (12 + 2)) << "rows reference, full, chain_L1";
    // levels.png: label column (96 px), then tiles of 16×12 below a 16 px header, legend last.
    const engine::Image picture = engine::read_png(folder / "out" / "levels.png");
    EXPECT_EQ(picture.width, 96 + 3 * (16 + 2));
    int lit_in_tiles = 0;
    for (int y = 16; y < 16 + 12; ++y)
        for (int x = 96; x < picture.width; ++x) lit_in_tiles += picture.pixel(x, y)[0] > 0;
    EXPECT_GT(lit_in_tiles, 0) << "the level tiles are missing from levels.png";
    std::ifstream report(folder / "out" / "report.md");
    std::stringstream text;
    text << report.rdbuf();
    EXPECT_NE(text.str().find("Matched Gaussian counts"), std::string::npos);
    EXPECT_NE(text.str().find("| 1× | chain_L0 (nearest) | 27 |"), std::string::npos) << text.str();
    EXPECT_NE(text.str().find("LOD verdict"), std::string::npos);
}

TEST_F(SplatEvalTest, UpscaleSweepScoresEveryUpscalerAgainstNative) {
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    eval::EvalScene scene = eval::make_splat_scene(small_cloud());
    const auto poses = eval::orbit_poses(scene.extent, {0, 1, 0}, 1);

    eval::EvalOptions options;
    options.scene_name = "tiny";
    options.width = 96;
    options.height = 64;
    options.frames = 1;
    options.warmup = 0;
    options.sweeps = {eval::Sweep::upscale};
    options.upscale_factors = {2, 3};  // every upscaler (the default list)
    int progress_lines = 0;
    options.progress = [&](const std::string& line) {
        ++progress_lines;
        EXPECT_NE(line.find("(upscale)"), std::string::npos) << line;
    };
    eval::FrameMeasurer measurer(engine, *scene.scene);
    const eval::EvalResults results = eval::run_evaluation(measurer, poses, options);
    EXPECT_EQ(progress_lines, 1 + 2 * 5);
    ASSERT_EQ(results.rows.size(), 11u);

    const auto& native = results.rows.front();
    ASSERT_EQ(native.method, "native");
    EXPECT_EQ(native.factor, 1);
    EXPECT_TRUE(std::isinf(*native.psnr)) << "native against the native reference must be exact";
    EXPECT_DOUBLE_EQ(*native.ssim, 1.0);
    for (const auto& row : results.rows) {
        EXPECT_EQ(row.sweep, eval::Sweep::upscale);
        EXPECT_EQ(row.width, 96) << "every upscaler's image is at the output size";
        EXPECT_EQ(row.height, 64);
        EXPECT_EQ(row.statistics.considered, 27u);
        ASSERT_TRUE(row.psnr && row.ssim);
        EXPECT_GT(row.wall_ms, 0.0);
        if (row.factor == 1) continue;
        // The pass upscaled (it timed splat.upscale): close to native, but not the native image.
        EXPECT_TRUE(row.gpu_ms.count("splat.upscale")) << row.method << " " << row.factor;
        EXPECT_TRUE(std::isfinite(*row.psnr)) << row.method << " " << row.factor;
        EXPECT_GT(*row.psnr, 30.0) << row.method << " " << row.factor;
    }
    const auto psnr_of = [&](const std::string& method, int factor) {
        for (const auto& row : results.rows)
            if (row.method == method && row.factor == factor) return *row.psnr;
        throw std::runtime_error("no row for " + method);
    };
    for (int f : {2, 3})
        EXPECT_GT(psnr_of("spline", f), psnr_of("spline_plain", f))
            << "the resolution-consistent dilation reaches the pass at " << f << "x";
    // Crops of the first view: native and the five upscalers at 3×.
    EXPECT_EQ(results.upscale_tiles.size(), 6u);

    const auto folder = engine::test::output_dir("splat_eval") / "tiny_upscale";
    std::filesystem::remove_all(folder);
    eval::write_outputs(results, "test", folder);
    const auto csv = read_lines(folder / "measurements.csv");
    ASSERT_EQ(csv.size(), 12u);
    EXPECT_EQ(csv[1].rfind("tiny,upscale,0,\"orbit 0\",native,1,96,64,inf,1.000000,", 0), 0u) << csv[1];
    EXPECT_EQ(csv[2].rfind("tiny,upscale,0,\"orbit 0\",spline,2,96,64,", 0), 0u) << csv[2];
    // One row (3×) of six 96×64 crops magnified 3×, under a label line, after the row labels.
    const engine::Image crops = engine::read_png(folder / "upscale_crops.png");
    EXPECT_EQ(crops.width, 40 + 6 * (288 + 2));
    EXPECT_EQ(crops.height, 16 + 192 + 2);
    std::ifstream report(folder / "report.md");
    std::stringstream text;
    text << report.rdbuf();
    EXPECT_NE(text.str().find("### Upscale sweep"), std::string::npos);
    EXPECT_NE(text.str().find("| 3\u00d7 | spline | 32\u00d722 |"), std::string::npos) << text.str();
    EXPECT_NE(text.str().find("Upscale verdict"), std::string::npos);
    EXPECT_EQ(text.str().find("### Scale sweep"), std::string::npos);
}

TEST_F(SplatEvalTest, UpscaleMethodsSetTheSplatPassAndBadFactorsFailFirst) {
    splat_lod::SplatPassSettings settings;
    plugin_msgs::LodSettings lod;
    const eval::UpscalerVariant plain = eval::select_upscalers("spline_plain").front();
    eval::upscaled_method(eval::find_method("full", "--upscale-mode"), plain, 4).configure(lod, settings);
    EXPECT_FLOAT_EQ(lod.render_scale, 0.25f);
    EXPECT_EQ(lod.upscaler, plugin_msgs::Upscaler::spline);
    EXPECT_FALSE(settings.scaled_dilation);
    EXPECT_EQ(lod.rule.mode, plugin_msgs::LodMode::full);
    settings = splat_lod::SplatPassSettings{};
    lod = plugin_msgs::LodSettings{};
    eval::upscaled_method(eval::reference_method(), eval::select_upscalers("lanczos3").front(), 3)
        .configure(lod, settings);
    EXPECT_FLOAT_EQ(lod.render_scale, 1.0f / 3.0f);
    EXPECT_EQ(lod.upscaler, plugin_msgs::Upscaler::lanczos3);
    EXPECT_TRUE(settings.scaled_dilation);
    eval::native_method(eval::reference_method()).configure(lod, settings);
    EXPECT_FLOAT_EQ(lod.render_scale, 1.0f);

    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    eval::EvalScene scene = eval::make_splat_scene(small_cloud());
    eval::FrameMeasurer measurer(engine, *scene.scene);
    eval::EvalOptions options;
    options.width = 96;
    options.height = 64;
    options.sweeps = {eval::Sweep::upscale};
    options.upscale_factors = {2, 32};
    bool rendered = false;
    options.progress = [&](const std::string&) { rendered = true; };
    try {
        eval::run_evaluation(measurer, eval::orbit_poses(scene.extent, {0, 1, 0}, 1), options);
        ADD_FAILURE() << "factor 32 does not fit 96x64";
    } catch (const engine::Error& e) {
        EXPECT_NE(std::string(e.what()).find("--upscale-factors: factor 32 is too large"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(rendered);
}

}  // namespace
