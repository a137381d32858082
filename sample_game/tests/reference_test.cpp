// The profile's reference (reference_run.h, reference_cache.h) on a tiny generated world of its own:
// a tiled render equals the untiled one (the tiles are off-centre windows of one camera), the
// reference is made, cached and found again without drawing, another size gets another folder, a
// damaged cached frame is an error naming it (and --force makes it again), and the profile reads
// the reference into psnr_vs_reference, ssim_vs_reference, seam_ratio and, on frames whose
// predecessor has a reference too, temporal_error, and draws its frame strip around the largest.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/engine.h"
#include "gpu_fixture.h"
#include "sample_game/game_world.h"
#include "sample_game/harness/frame_record.h"
#include "sample_game/harness/profile_run.h"
#include "sample_game/harness/reference_run.h"
#include "sample_game/world_path.h"
#include "splat_lod/eval/sheet_drawing.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/worldgen/world_generator.h"
#include "test_support.h"
#include "tiny_world.h"

namespace fs = std::filesystem;
namespace sw = splat_lod::world;
using namespace sample_game;

namespace {

// The reference tests draw a tiny world of their own ("reference_world"): its reference/ folder is theirs.
class ReferenceTest : public engine::test::GpuTest {};

ReferenceOptions small_reference(const fs::path& world) {
    ReferenceOptions o;
    o.world = world;
    o.width = 64;
    o.height = 36;
    o.frames = 20;
    o.settings.sync_streaming = true;
    o.max_render_side = 100;  // 192 × 108 at 3×: drawn in 2 × 2 tiles
    return o;
}

double largest_difference(const splat_lod::eval::FloatImage& a, const splat_lod::eval::FloatImage& b) {
    double largest = 0.0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) largest = std::max(largest, double(std::abs(a.rgb[i] - b.rgb[i])));
    return largest;
}

}  // namespace

TEST_F(ReferenceTest, ATiledRenderEqualsTheUntiledOne) {
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    GameSettings settings;
    settings.sync_streaming = true;
    GameWorld world(engine, engine::test::cached_tiny_world("reference_world"), settings);
    world.load_whole_world({});
    plugin_msgs::LodSettings lod;
    lod.rule.mode = plugin_msgs::LodMode::baseline;
    engine.bus().publish(lod);
    const std::vector<PathPose> poses = world.path(20);
    // A ground, a flyout and an overview view, at a size the tiles do not divide evenly.
    for (const std::size_t frame : {std::size_t(1), std::size_t(9), std::size_t(13)}) {
        SCOPED_TRACE("path frame " + std::to_string(frame));
        const engine::CameraView camera = world.camera(poses[frame], 150, 94);
        const auto whole = render_tiled(engine, world.scene(), camera, 4096);
        const auto tiled = render_tiled(engine, world.scene(), camera, 40);  // 4 × 3 tiles
        const double psnr = splat_lod::eval::psnr(tiled, whole);
        EXPECT_TRUE(std::isinf(psnr) || psnr > 60.0) << psnr << " dB";
        EXPECT_LE(largest_difference(tiled, whole), 1.0 / 255.0);  // identical on llvmpipe
        double sum = 0.0;
        for (const float v : whole.rgb) sum += v;
        EXPECT_GT(sum, 0.0);
    }
}

TEST_F(ReferenceTest, IsMadeCachedAndFoundAgain) {
    const fs::path world = engine::test::cached_tiny_world("reference_world");
    fs::remove_all(world / kReferenceFolderName);
    ReferenceOptions o = small_reference(world);
    const ReferenceOutcome made = make_reference(o, nullptr);
    EXPECT_FALSE(made.cached);
    ASSERT_GE(made.frames.size(), 8u);
    EXPECT_EQ(made.folder.parent_path(), world / kReferenceFolderName);
    const std::vector<PathPose> poses = [&] {
        const sw::WorldManifest m = sw::read_world_manifest(world / sw::kManifestFileName);
        return sample_world_path(sw::WorldTerrain(m.seed, m.size_m, m.feature_scale()), 20);
    }();
    std::set<Segment> segments;
    const std::set<std::size_t> made_frames(made.frames.begin(), made.frames.end());
    for (const std::size_t f : made.frames) {
        EXPECT_TRUE(made_frames.count(f + 1) || (f > 0 && made_frames.count(f - 1)))
            << "frame " << f << " comes with its successor";
        segments.insert(poses.at(f).segment);
        const engine::Image image = engine::read_png(reference_frame_file(made.folder, f));
        EXPECT_EQ(image.width, 64);
        EXPECT_EQ(image.height, 36);
    }
    EXPECT_EQ(segments.size(), kSegmentCount) << "reference frames in every segment";
    const std::string key = engine::read_text_file(made.folder / "reference.json");
    for (const char* field :
         {"world_chunks_crc32", "\"width\": 64", "\"supersample\": 3", "format_version", "fov_y_deg"})
        EXPECT_NE(key.find(field), std::string::npos) << key;
    std::size_t entries = 0;
    for (const auto& entry : fs::directory_iterator(world / kReferenceFolderName)) {
        ++entries;
        EXPECT_EQ(entry.path().filename().string().rfind(".tmp-", 0), std::string::npos) << "no temporary left";
    }
    EXPECT_EQ(entries, 1u);

    // Found again: nothing drawn, nothing rewritten.
    const auto written = fs::last_write_time(reference_frame_file(made.folder, made.frames.front()));
    const ReferenceOutcome again = make_reference(o, nullptr);
    EXPECT_TRUE(again.cached);
    EXPECT_EQ(again.folder, made.folder);
    EXPECT_EQ(fs::last_write_time(reference_frame_file(made.folder, made.frames.front())), written);
    EXPECT_NE(again.text.find("nothing to do"), std::string::npos) << again.text;

    // Another width is another key.
    o.width = 72;
    const ReferenceOutcome wider = make_reference(o, nullptr);
    EXPECT_FALSE(wider.cached);
    EXPECT_NE(wider.folder, made.folder);
    EXPECT_TRUE(fs::exists(made.folder / "reference.json")) << "the other key's reference stays";
}

TEST_F(ReferenceTest, ADamagedCachedFrameIsAnErrorNamingItUntilMadeAgain) {
    const fs::path world = engine::test::cached_tiny_world("reference_world");
    ReferenceOptions o = small_reference(world);
    const ReferenceOutcome made = make_reference(o, nullptr);  // made or cached
    const fs::path victim = reference_frame_file(made.folder, made.frames.back());
    const std::vector<std::uint8_t> bytes = engine::read_binary_file(victim);
    engine::write_file_atomic(victim, std::span(bytes.data(), bytes.size() / 2));
    try {
        make_reference(o, nullptr);
        FAIL() << "a truncated frame was accepted";
    } catch (const engine::Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(victim.string()), std::string::npos) << message;
        EXPECT_NE(message.find("--force"), std::string::npos) << message;
    }
    o.force = true;
    const ReferenceOutcome remade = make_reference(o, nullptr);
    EXPECT_FALSE(remade.cached);
    EXPECT_EQ(engine::read_png(victim).width, 64);
    o.force = false;
    EXPECT_TRUE(make_reference(o, nullptr).cached);
}

TEST_F(ReferenceTest, TheProfileComparesItsFramesWithTheReference) {
    const fs::path world = engine::test::cached_tiny_world("reference_world");
    const ReferenceOptions r = small_reference(world);
    const ReferenceOutcome reference = make_reference(r, nullptr);
    const std::set<std::size_t> frames(reference.frames.begin(), reference.frames.end());
    ProfileOptions o;
    o.world = world;
    o.out = engine::test::output_dir("sample_game") / "profile_with_reference";
    fs::remove_all(o.out);
    o.width = r.width;
    o.height = r.height;
    o.frames = r.frames;
    o.baseline_every = 0;  // the overview and the reference frames only
    o.settings.sync_streaming = true;
    const ProfileOutcome outcome = run_profile(o, nullptr);

    const CsvTable lod = read_csv(o.out / "profile.csv");
    ASSERT_EQ(lod.rows.size(), 20u);
    int seams = 0, pairs = 0;
    for (std::size_t row = 0; row < lod.rows.size(); ++row) {
        SCOPED_TRACE("profile.csv row " + std::to_string(row));
        const double psnr = lod.number(row, "psnr_vs_reference"), ssim = lod.number(row, "ssim_vs_reference");
        const double seam = lod.number(row, "seam_ratio"), temporal = lod.number(row, "temporal_error");
        const double seam_same_distance = lod.number(row, "seam_ratio_same_distance");
        if (frames.count(row) && row > 0 && frames.count(row - 1)) {
            ++pairs;
            EXPECT_TRUE(temporal >= 0.0 && temporal < 64.0) << temporal;
        } else {
            EXPECT_EQ(temporal, -1.0) << "no reference for this frame or the one before";
        }
        if (frames.count(row)) {
            EXPECT_GT(psnr, 10.0);
            EXPECT_TRUE(ssim > 0.0 && ssim <= 1.0) << ssim;
            EXPECT_TRUE(seam == -1.0 || seam > 0.0) << seam;
            EXPECT_TRUE(seam_same_distance == -1.0 || seam_same_distance > 0.0) << seam_same_distance;
            EXPECT_EQ(seam_same_distance > 0.0, seam > 0.0) << "both measures see the same borders";
            seams += seam > 0.0 ? 1 : 0;
        } else {
            EXPECT_EQ(psnr, -1.0);
            EXPECT_EQ(ssim, -1.0);
            EXPECT_EQ(seam, -1.0);
            EXPECT_EQ(seam_same_distance, -1.0);
        }
    }
    EXPECT_GE(seams, 4) << "chunk borders are in view on most reference frames";
    const CsvTable baseline = read_csv(o.out / "baseline.csv");
    std::set<std::size_t> compared;
    for (std::size_t row = 0; row < baseline.rows.size(); ++row) {
        const auto frame = static_cast<std::size_t>(baseline.number(row, "frame"));
        const double seam = baseline.number(row, "seam_ratio");
        if (!frames.count(frame)) {
            EXPECT_EQ(seam, -1.0);
            continue;
        }
        EXPECT_TRUE(seam == -1.0 || seam > 0.0) << "the baseline's seam_ratio, for comparison: " << seam;
        const double temporal = baseline.number(row, "temporal_error");
        EXPECT_EQ(temporal >= 0.0, frame > 0 && frames.count(frame - 1) > 0) << "frame " << frame << ": " << temporal;
        compared.insert(frame);
        EXPECT_GT(baseline.number(row, "psnr_vs_reference"), 10.0);
        EXPECT_GT(baseline.number(row, "ssim_vs_reference"), 0.0);
    }
    EXPECT_EQ(compared, frames) << "the baseline draws every reference frame";
    EXPECT_EQ(outcome.summary.reference_frames.size(), frames.size());
    EXPECT_GE(pairs, 6) << "each chosen frame with its successor";
    EXPECT_EQ(outcome.summary.lod_temporal.pairs, pairs);
    EXPECT_EQ(outcome.summary.baseline_temporal.pairs, pairs);
    // The strip: six consecutive LOD frames around the largest temporal error, the reference above
    // where it exists, the temporal error's picture below.
    const engine::Image strip = engine::read_png(o.out / "frames_strip.png");
    EXPECT_EQ(strip.width, 6 * (r.width + 2));
    EXPECT_EQ(strip.height, 3 * (r.height + splat_lod::eval::kLabelHeight + 2));
    const std::string& summary = outcome.summary_text;
    EXPECT_NE(summary.find("frames_strip.png: LOD frames"), std::string::npos) << summary;
    EXPECT_NE(summary.find("around the largest temporal_error (frame " +
                           std::to_string(outcome.summary.lod_temporal.largest_frame)),
              std::string::npos)
        << summary;
    EXPECT_NE(summary.find("temporal_error (mean"), std::string::npos) << summary;
    EXPECT_NE(summary.find("reference: found, " + reference.folder.string()), std::string::npos) << summary;
    EXPECT_NE(summary.find("against the reference"), std::string::npos) << summary;
    EXPECT_NE(summary.find("reference, LOD vs baseline"), std::string::npos) << summary;
    EXPECT_NE(summary.find("reference, seams"), std::string::npos) << summary;
}
