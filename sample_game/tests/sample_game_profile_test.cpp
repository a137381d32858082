// sample_game on a tiny generated world through the real engine (headless EGL): the profile walks
// the whole path with binding budgets and writes one CSV row per frame with the documented
// columns, budgets respected on every frame, the baseline's frames, plots, frames and summary;
// the world's props and terrain mesh become mesh nodes, an imported world's far layer a splat node;
// loading the whole world holds exactly its bytes on the GPU.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/engine.h"
#include "engine/render/render_target.h"
#include "engine/scene/builtin_components.h"
#include "gpu_fixture.h"
#include "sample_game/game_world.h"
#include "sample_game/harness/frame_record.h"
#include "sample_game/harness/profile_run.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/eval/sheet_drawing.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "splat_lod/stream/stream_policy.h"
#include "splat_lod/worldgen/world_generator.h"
#include "splat_lod/worldgen/world_import.h"
#include "test_support.h"
#include "tiny_world.h"

namespace sw = splat_lod::world;
using namespace sample_game;

namespace {

class SampleGameTest : public engine::test::GpuTest {};

// GPU bytes of the whole world at SH degree 0, every stream level in whole pages.
std::uint64_t whole_world_bytes(const sw::WorldManifest& m) {
    std::uint64_t total = 0;
    for (const auto& c : m.chunks)
        for (int l = 1; l <= sw::kLevels; ++l) {
            const std::uint64_t count = c.prefix_count[static_cast<std::size_t>(l - 1)] -
                                        (l < sw::kLevels ? c.prefix_count[static_cast<std::size_t>(l)] : 0);
            total += sw::gpu_bytes(count, 0, sw::PageLayout{});
        }
    return total;
}

}  // namespace

TEST_F(SampleGameTest, ProfileWalksThePathWithinItsBudgetsAndWritesEveryOutput) {
    const auto world = engine::test::cached_tiny_world("tiny_world");
    const sw::WorldManifest manifest = sw::read_world_manifest(world / sw::kManifestFileName);
    const std::uint64_t page = sw::gpu_bytes(256, 0, sw::PageLayout{});
    ProfileOptions o;
    o.world = world;
    o.out = engine::test::output_dir("sample_game") / "profile";
    std::filesystem::remove_all(o.out);
    o.width = 160;
    o.height = 90;
    o.frames = 24;
    o.frames_png_every = 8;
    o.baseline_every = 6;
    o.settings.sync_streaming = true;
    // Binding budgets: less than the whole world may be resident, two pages per frame uploaded.
    o.settings.memory_budget_bytes = whole_world_bytes(manifest) * 6 / 10 / page * page;
    o.settings.upload_budget_bytes = 2 * page;
    ASSERT_GT(o.settings.memory_budget_bytes, 4 * page);
    const ProfileOutcome outcome = run_profile(o, nullptr);

    const CsvTable lod = read_csv(o.out / "profile.csv");
    ASSERT_EQ(lod.rows.size(), 24u) << "one row per path frame";
    ASSERT_EQ(lod.header.size(), frame_columns().size());
    for (std::size_t i = 0; i < frame_columns().size(); ++i) EXPECT_EQ(lod.header[i], frame_columns()[i].name);
    std::set<std::string> segments;
    double peak = 0.0, drawn = 0.0;
    for (std::size_t r = 0; r < lod.rows.size(); ++r) {
        SCOPED_TRACE("profile.csv row " + std::to_string(r));
        EXPECT_EQ(lod.number(r, "frame"), static_cast<double>(r));
        segments.insert(lod.rows[r][lod.column("segment")]);
        EXPECT_LE(lod.number(r, "resident_bytes"), static_cast<double>(o.settings.memory_budget_bytes));
        EXPECT_EQ(lod.number(r, "gpu_page_bytes"), lod.number(r, "resident_bytes") + lod.number(r, "props_gpu_bytes"));
        // The splat pass's total is its scene buffers and its frame buffers (frames with statistics).
        if (lod.number(r, "gpu_total_bytes") > 0.0) {
            EXPECT_EQ(lod.number(r, "gpu_total_bytes"),
                      lod.number(r, "gpu_scene_bytes") + lod.number(r, "gpu_frame_bytes"));
            EXPECT_GE(lod.number(r, "gpu_scene_bytes"), lod.number(r, "gpu_page_bytes"));
        }
        EXPECT_LE(lod.number(r, "upload_bytes"), static_cast<double>(o.settings.upload_budget_bytes));
        EXPECT_EQ(lod.number(r, "failures_total"), 0.0);
        EXPECT_GT(lod.number(r, "frame_ms"), 0.0);
        EXPECT_GE(lod.number(r, "height_m"), 1.0);
        const double states = lod.number(r, "chunks_absent") + lod.number(r, "chunks_requested") +
                              lod.number(r, "chunks_loaded") + lod.number(r, "chunks_partial") +
                              lod.number(r, "chunks_resident");
        EXPECT_EQ(states, static_cast<double>(manifest.chunks.size()));
        peak = std::max(peak, lod.number(r, "resident_bytes"));
        drawn = std::max(drawn, lod.number(r, "visible"));
    }
    EXPECT_EQ(segments, (std::set<std::string>{"ground", "canopy", "flyout", "overview", "return"}));
    EXPECT_GT(peak, 0.5 * static_cast<double>(o.settings.memory_budget_bytes)) << "the view filled in up to the budget";
    EXPECT_GT(drawn, 1000.0);

    const CsvTable baseline = read_csv(o.out / "baseline.csv");
    int overview_frames = 0;
    for (std::size_t r = 0; r < lod.rows.size(); ++r)
        overview_frames += lod.rows[r][lod.column("segment")] == "overview" ? 1 : 0;
    EXPECT_GE(static_cast<int>(baseline.rows.size()), overview_frames + 2);
    for (std::size_t r = 0; r < baseline.rows.size(); ++r) {
        SCOPED_TRACE("baseline.csv row " + std::to_string(r));
        EXPECT_EQ(baseline.rows[r][baseline.column("run")], "baseline");
        EXPECT_EQ(baseline.number(r, "resident_bytes"), static_cast<double>(whole_world_bytes(manifest)));
        EXPECT_EQ(baseline.number(r, "drawn_l2") + baseline.number(r, "drawn_l3") + baseline.number(r, "drawn_l4"), 0.0)
            << "baseline mode draws level 1 only";
        // Every baseline frame is one the LOD run drew too: its image was compared (a PSNR in dB and an
        // SSIM in (0, 1], not a placeholder).
        const double psnr = baseline.number(r, "psnr_lod_vs_baseline"),
                     ssim = baseline.number(r, "ssim_lod_vs_baseline");
        EXPECT_TRUE(std::isfinite(psnr) && psnr > 5.0) << psnr;
        EXPECT_TRUE(ssim > 0.0 && ssim <= 1.0) << ssim;
    }

    EXPECT_TRUE(outcome.plot_problem.empty()) << outcome.plot_problem << " (scripts/setup installs gnuplot-nox)";
    for (const char* name :
         {"frame_time.png", "memory.png", "gaussians.png", "frames_sheet.png", "frames/lod_0000_ground.png"})
        EXPECT_TRUE(std::filesystem::exists(o.out / name)) << name;
    int lod_pictures = 0;
    for (const auto& entry : std::filesystem::directory_iterator(o.out / "frames"))
        lod_pictures += entry.path().filename().string().rfind("lod_", 0) == 0 ? 1 : 0;
    EXPECT_EQ(lod_pictures, 3) << "frames 0, 8 and 16 of 24";
    const engine::Image sheet = engine::read_png(o.out / "frames_sheet.png");
    EXPECT_GT(sheet.width, 160);
    // Without a reference the strip shows the overview's first six frames alone.
    const engine::Image strip = engine::read_png(o.out / "frames_strip.png");
    EXPECT_EQ(strip.width, 6 * (160 + 2));
    EXPECT_EQ(strip.height, 90 + splat_lod::eval::kLabelHeight + 2);
    const std::string summary = engine::read_text_file(o.out / "summary.txt");
    EXPECT_EQ(summary, outcome.summary_text);
    EXPECT_NE(summary.find("PASS  memory"), std::string::npos) << summary;
    EXPECT_NE(summary.find("PASS  upload"), std::string::npos) << summary;
    EXPECT_NE(summary.find("overview: LOD+streaming"), std::string::npos) << summary;
    EXPECT_NE(summary.find("first view preloaded in"), std::string::npos) << summary;
    EXPECT_NE(summary.find("(the overview's first; no reference"), std::string::npos) << summary;
}

TEST_F(SampleGameTest, WorldPutsPropsAndTerrainInTheSceneAndCanHoldAllOfIt) {
    const auto world_folder = engine::test::cached_tiny_world("tiny_world");
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    GameSettings settings;
    settings.sync_streaming = true;
    GameWorld world(engine, world_folder, settings);
    const auto& m = world.manifest();
    ASSERT_FALSE(m.props.empty());
    ASSERT_FALSE(m.terrain_mesh.empty());
    EXPECT_EQ(world.scene().components<engine::MeshComponent>().size(), m.props.size() + 1);
    const ChunkCensus before = world.census();
    EXPECT_EQ(before.finest_resident[0], m.chunks.size()) << "nothing resident before the first update";
    EXPECT_EQ(world.whole_world_gpu_bytes(), whole_world_bytes(m));

    world.load_whole_world({});
    EXPECT_EQ(world.streamer().resident_bytes(), whole_world_bytes(m));
    // Drawn whole from the first frame on: no part still fading in (the baseline and the reference
    // draw right after the load; settings.fade_frames is the game's, 4 by default).
    std::size_t splat_parts = 0;
    for (const auto* part : world.scene().components<splat_lod::SplatComponent>()) {
        if (!part->visible) continue;
        ++splat_parts;
        EXPECT_EQ(part->opacity, 1.0f);
    }
    EXPECT_GT(splat_parts, m.chunks.size()) << "every chunk's levels shown";
    EXPECT_EQ(world.census().finest_resident[1], m.chunks.size());
    engine::RenderTarget target(96, 64);
    splat_lod::render_complete(engine, world.scene(), world.camera({0.0f, 60.0f, 60.0f}, {0.0f, -1.0f, -1.0f}, 96, 64),
                               target);
    EXPECT_EQ(std::uint64_t(world.pass().memory().pages_in_use) * world.pass().memory().page_bytes,
              whole_world_bytes(m));
}

// An imported capture's far layer (a splat glTF prop) is drawn beside the streamed chunks, and the GPU holds
// exactly the streamer's pages plus the far layer's.
TEST_F(SampleGameTest, AnImportedWorldDrawsItsFarLayerBesideTheChunks) {
    const auto dir = engine::test::output_dir("sample_game") / "imported";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    splat_lod::SplatCloud capture;  // 64 × 64 ground Gaussians over 32 units and two huge ones above them
    capture.resize(64 * 64 + 2);
    for (std::size_t k = 0; k < 64 * 64; ++k) {
        capture.positions[k] = {-16.0f + 0.5f * static_cast<float>(k % 64), 0.0f,
                                -16.0f + 0.5f * static_cast<float>(k / 64)};
        capture.log_scales[k] = {std::log(0.3f), std::log(0.01f), std::log(0.3f)};
        capture.opacity_logits[k] = 3.0f;
        capture.sh_dc[k] = {0.4f, 0.6f, 0.2f};
    }
    for (std::size_t k = 64 * 64; k < capture.size(); ++k) {
        capture.positions[k] = {k % 2 == 0 ? -6.0f : 6.0f, 20.0f, 0.0f};
        capture.log_scales[k] = glm::vec3(std::log(25.0f));
        capture.opacity_logits[k] = -2.0f;
    }
    splat_lod::write_inria_ply(dir / "capture.ply", capture);
    sw::ImportOptions import;
    import.capture = dir / "capture.ply";
    import.output = dir / "world";
    import.max_chunk_gaussians = 1024;
    import.bake.refine_iterations = 0;
    import.bake_width = import.bake_height = 64;
    const sw::ImportResult imported = sw::import_world(import);
    ASSERT_EQ(imported.manifest.props.size(), 1u) << "the far layer";
    ASSERT_GE(imported.summary.far_layer, 2u);

    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    GameSettings settings;
    settings.sync_streaming = true;
    GameWorld world(engine, dir / "world", settings);
    const auto splats = world.scene().components<splat_lod::SplatComponent>();
    ASSERT_EQ(splats.size(), 1u) << "before any update, only the far layer";
    EXPECT_EQ(splats[0]->cloud->size(), imported.summary.far_layer);
    EXPECT_EQ(world.props_gpu_bytes(),
              sw::gpu_bytes(imported.summary.far_layer, std::min(3, splats[0]->cloud->sh_degree), sw::PageLayout{}));
    engine::RenderTarget target(96, 64);
    const auto camera = world.camera({0.0f, 30.0f, 30.0f}, glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f)), 96, 64);
    for (std::uint64_t frame = 0; frame < 6; ++frame) {
        world.update_streaming(camera, frame);
        splat_lod::render_complete(engine, world.scene(), camera, target);
    }
    EXPECT_GT(world.streamer().resident_bytes(), 0u);
    EXPECT_EQ(std::uint64_t(world.pass().memory().pages_in_use) * world.pass().memory().page_bytes,
              world.streamer().resident_bytes() + world.props_gpu_bytes());
}

TEST(SampleGameWorld, AMissingWorldSaysHowToMakeIt) {
    const auto folder = engine::test::output_dir("sample_game") / "no_world_here";
    try {
        require_world_folder(folder);
        FAIL() << "no error";
    } catch (const engine::Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find((folder / "world.json").string() + ": not found"), std::string::npos) << message;
        EXPECT_NE(message.find("splat_world --out"), std::string::npos) << message;
    }
}
