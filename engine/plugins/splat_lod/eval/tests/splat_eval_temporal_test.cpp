// The temporal sweep end to end on a tiny synthetic cloud: baseline and full on a short dolly, an
// orbit and a camera-path file; temporal.csv, the plots and the strips.
#include <cmath>
#include <fstream>

#include "gpu_fixture.h"
#include "splat_lod/eval/eval_scene.h"
#include "splat_lod/eval/frame_measurer.h"
#include "splat_lod/eval/temporal_sweep.h"
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

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
        fields.push_back(line.substr(start, comma - start));
    fields.push_back(line.substr(start));
    return fields;
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

// Four cameras stepping sideways past the cube.
void write_camera_path(const std::filesystem::path& file) {
    std::ofstream out(file);
    out << "[";
    for (int i = 0; i < 4; ++i)
        out << (i ? "," : "") << R"({"eye": [)" << 0.2 * i - 0.3 << R"(, 0.5, 3.5], "target": [0, 0, 0]})";
    out << "]";
}

// Six rows (two methods on three paths) with finite errors; baseline's small.
void expect_rows_and_strips(const eval::TemporalResults& results) {
    ASSERT_EQ(results.rows.size(), 6u);
    for (const auto& row : results.rows) {
        SCOPED_TRACE(row.method + " on " + row.path);
        EXPECT_EQ(row.pair_errors.size(), static_cast<std::size_t>(row.frames - 1));
        EXPECT_EQ(row.pair_pops.size(), row.pair_errors.size());
        EXPECT_GE(row.pop_peak, row.pop_mean);
        EXPECT_EQ(row.pair_switch_pops.size(), row.pair_errors.size());
        EXPECT_GE(row.switch_pop_peak, row.switch_pop_mean);
        EXPECT_TRUE(std::isfinite(row.temporal_error));
        EXPECT_GT(row.temporal_error, 0.0) << "the low-resolution render never moves exactly like the reference";
        EXPECT_TRUE(std::isfinite(row.psnr_mean));
        EXPECT_GT(row.psnr_mean, 20.0);
        ASSERT_TRUE(row.splat_ms_mean.has_value());
        EXPECT_GT(*row.splat_ms_mean, 0.0);
        if (row.method == "baseline") {
            EXPECT_LT(row.temporal_error, 3.0) << "the reference's own renderer";
            EXPECT_EQ(row.switch_pop_peak, 0.0) << "no selection: the previous frame's draws the same bytes";
        }
    }
    ASSERT_EQ(results.strips.size(), 3u);
    for (const auto& strip : results.strips) {
        EXPECT_EQ(strip.rows, (std::vector<std::string>{"reference", "baseline", "full"}));
        EXPECT_EQ(strip.differences.size(), static_cast<std::size_t>(eval::kStripFrames - 1));
        EXPECT_GE(strip.peak_frame, strip.first_frame + 1);
        EXPECT_LE(strip.peak_frame, strip.first_frame + eval::kStripFrames - 1);
    }
}

// temporal.csv, temporal.md, a plot and a strip per path.
void expect_files(const std::filesystem::path& folder) {
    const auto csv = read_lines(folder / "temporal.csv");
    ASSERT_EQ(csv.size(), 7u);
    EXPECT_EQ(csv[0],
              "method,path,frames,temporal_error,psnr_mean,splat_ms_mean,pop_peak,pop_mean,switch_pop_peak,"
              "switch_pop_mean");
    EXPECT_EQ(csv[1].rfind("baseline,dolly,8,", 0), 0u) << csv[1];
    EXPECT_EQ(csv[6].rfind("full,side_step,4,", 0), 0u) << csv[6];
    for (std::size_t i = 1; i < csv.size(); ++i) {
        const auto fields = split(csv[i]);
        ASSERT_EQ(fields.size(), 10u) << csv[i];
        for (std::size_t f = 3; f < fields.size(); ++f) EXPECT_TRUE(std::isfinite(std::stod(fields[f]))) << csv[i];
    }
    for (const std::string path : {"dolly", "orbit", "side_step"}) {
        EXPECT_TRUE(std::filesystem::exists(folder / ("temporal_" + path + ".png"))) << path;
        const engine::Image strip = engine::read_png(folder / ("temporal_strip_" + path + ".png"));
        EXPECT_EQ(strip.width, 96 + 4 * (64 + 2));
        EXPECT_EQ(strip.height, 16 + 4 * (48 + 2) + 16) << "reference, 2 methods, differences, caption";
    }
    EXPECT_TRUE(std::filesystem::exists(folder / "temporal.md"));
}

class SplatEvalTemporalTest : public engine::test::GpuTest {};

TEST_F(SplatEvalTemporalTest, SweepWritesOneRowPerMethodAndPathWithPlotsAndStrips) {
    const auto folder = engine::test::output_dir("splat_eval") / "tiny_temporal";
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    write_camera_path(folder / "side step.json");
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    eval::EvalScene scene = eval::make_splat_scene(small_cloud());
    const glm::vec3 up(0, 1, 0);

    eval::TemporalOptions options;
    options.scene_name = "tiny";
    options.width = 64;
    options.height = 48;
    options.methods = eval::select_methods("baseline,full");
    options.dolly_frames = 8;
    options.paths = "dolly,orbit";
    options.path_file = (folder / "side step.json").string();
    int progress_lines = 0;
    options.progress = [&](const std::string& line) {
        ++progress_lines;
        EXPECT_NE(line.find("(temporal)"), std::string::npos) << line;
    };
    std::vector<eval::TemporalPath> paths =
        eval::temporal_paths(options, eval::orbit_poses(scene.extent, up, 1).front(), scene.extent, up);
    ASSERT_EQ(paths.size(), 3u);
    EXPECT_EQ(paths[0].name, "dolly");
    EXPECT_EQ(paths[1].name, "orbit");
    EXPECT_EQ(paths[1].poses.size(), 24u);
    EXPECT_EQ(paths[2].name, "side_step");
    paths[1].poses = eval::orbit_path(scene.extent, up, 6);  // a shorter orbit keeps the test quick

    eval::FrameMeasurer measurer(engine, *scene.scene);
    const eval::TemporalResults results = eval::run_temporal_sweep(measurer, paths, options);
    EXPECT_EQ(progress_lines, (8 + 6 + 4) + 3 * eval::kStripFrames);
    EXPECT_EQ(results.supersampling, 4);
    expect_rows_and_strips(results);

    eval::write_temporal_outputs(results, "test", folder / "out");
    expect_files(folder / "out");
}

}  // namespace
