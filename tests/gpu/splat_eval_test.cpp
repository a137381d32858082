// splat_eval end to end on a tiny synthetic cloud: both sweeps, every output file.
#include <cmath>
#include <fstream>
#include <sstream>

#include "gpu_fixture.h"
#include "splat_lod/eval/eval_report.h"
#include "splat_lod/eval/eval_run.h"
#include "splat_lod/eval/eval_scene.h"
#include "splat_lod/eval/frame_measurer.h"
#include "splat_lod/splat_lod_plugin.h"
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
                               static_cast<float>(i / 9) - 1.0f) * 0.6f;
        s.log_scale = glm::vec3(-1.6f);
        s.color = glm::vec3(0.2f + 0.3f * static_cast<float>(i % 3), 0.3f, 0.9f - 0.3f * static_cast<float>(i / 9));
        specs.push_back(s);
    }
    return std::make_shared<const splat_lod::SplatCloud>(engine::test::make_cloud(specs));
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
    EXPECT_GT(*first.psnr, 60.0) << "the baseline at scale 1 is its own reference";
    EXPECT_NEAR(*first.ssim, 1.0, 1e-6);
    EXPECT_GT(first.statistics.visible, 0u);

    const auto folder = engine::test::output_dir("splat_eval") / "tiny";
    std::filesystem::remove_all(folder);
    eval::write_outputs(results, "test", folder);
    const auto csv = read_lines(folder / "measurements.csv");
    ASSERT_EQ(csv.size(), 15u);
    EXPECT_EQ(csv[0].rfind("scene,sweep,view,view_name,method,factor,width,height,psnr_db,ssim,wall_ms", 0), 0u);
    EXPECT_EQ(csv[1].rfind("tiny,scale,0,\"orbit 0\",baseline,1,64,48,", 0), 0u) << csv[1];
    for (const char* file : {"report.md", "contact_sheet.png", "time_vs_error.png", "time_vs_distance.png",
                             "gaussians_vs_distance.png"})
        EXPECT_TRUE(std::filesystem::exists(folder / file)) << file;
    const engine::Image sheet = engine::read_png(folder / "contact_sheet.png");
    EXPECT_EQ(sheet.width, 96 + 4 * (16 + 2));
    std::ifstream report(folder / "report.md");
    std::stringstream text;
    text << report.rdbuf();
    EXPECT_NE(text.str().find("| baseline_mip |"), std::string::npos);
}

}  // namespace
