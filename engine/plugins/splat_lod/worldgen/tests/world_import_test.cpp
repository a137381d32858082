// A capture imported as a streamed world (world_import.h): the frame found from the data, the cut
// capture drawing like the uncut file, the out-of-core path under a tiny cap giving the same bytes, the
// hard cases counted or refused with the capture named, and a failed import keeping the previous world.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/render/camera.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/capture_source.h"
#include "splat_lod/core/chunk_quadtree.h"
#include "splat_lod/core/cloud_transform.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/worldgen/world_import.h"
#include "test_support.h"

namespace fs = std::filesystem;
namespace world = splat_lod::world;
using splat_lod::SplatCloud;

using splat_io_test::error_of;

namespace {

// A 40 × 30 unit patch of flat ground Gaussians (y up) with clusters of round "leaves" standing on it,
// four huge sky Gaussians and three floaters far away: 6,000 + 1,600 + 7 Gaussians.
SplatCloud synthetic_capture() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    SplatCloud cloud;
    cloud.resize(7607);
    std::size_t k = 0;
    for (int i = 0; i < 100; ++i)
        for (int j = 0; j < 60; ++j, ++k) {
            cloud.positions[k] = {-20.0f + 0.4f * static_cast<float>(i), 0.05f * unit(rng),
                                  -15.0f + 0.5f * static_cast<float>(j)};
            cloud.log_scales[k] = {std::log(0.3f), std::log(0.01f), std::log(0.3f)};
            cloud.opacity_logits[k] = 3.0f;
            cloud.sh_dc[k] = {0.5f * unit(rng), 0.8f * unit(rng), 0.2f};
        }
    for (int tree = 0; tree < 16; ++tree) {
        const glm::vec3 base(-16.0f + 32.0f * unit(rng), 0.0f, -12.0f + 24.0f * unit(rng));
        for (int leaf = 0; leaf < 100; ++leaf, ++k) {
            cloud.positions[k] = base + glm::vec3(unit(rng) - 0.5f, 1.0f + 3.0f * unit(rng), unit(rng) - 0.5f);
            cloud.log_scales[k] = glm::vec3(std::log(0.05f));
            cloud.opacity_logits[k] = 1.0f;
            cloud.sh_dc[k] = {-0.5f, 0.6f * unit(rng), -0.3f};
        }
    }
    for (int sky = 0; sky < 4; ++sky, ++k) {  // far bigger than any chunk
        cloud.positions[k] = {-10.0f + 7.0f * static_cast<float>(sky), 30.0f, 0.0f};
        cloud.log_scales[k] = glm::vec3(std::log(40.0f));
        cloud.opacity_logits[k] = -3.0f;
        cloud.sh_dc[k] = {0.3f, 0.5f, 1.2f};
    }
    for (int floater = 0; floater < 3; ++floater, ++k) {  // far outside the footprint
        cloud.positions[k] = {500.0f + 10.0f * static_cast<float>(floater), 2.0f, -400.0f};
        cloud.log_scales[k] = glm::vec3(std::log(0.2f));
        cloud.opacity_logits[k] = 2.0f;
    }
    return cloud;
}

// The capture as a Y-down INRIA file would hold it: a half turn about x.
SplatCloud y_down(SplatCloud cloud) {
    splat_lod::transform_cloud(cloud, splat_lod::rotation_between({0, 1, 0}, {0, -1, 0}), glm::dvec3(0.0));
    return cloud;
}

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = engine::test::output_dir("world_import") / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// A fast recipe: small chunks, small cameras, no refinement (the test is about the import, not the bake).
world::ImportOptions fast_options(const fs::path& capture, const fs::path& output) {
    world::ImportOptions o;
    o.capture = capture;
    o.output = output;
    o.max_chunk_gaussians = 2048;
    o.bake.refine_iterations = 0;
    o.bake_width = 64;
    o.bake_height = 64;
    o.threads = 2;
    return o;
}

double psnr(const splat_lod::reference::ReferenceImage& a, const splat_lod::reference::ReferenceImage& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const double d = std::clamp(a.rgb[i], 0.0, 1.0) - std::clamp(b.rgb[i], 0.0, 1.0);
        sum += d * d;
    }
    const double mse = sum / static_cast<double>(a.rgb.size());
    return mse == 0.0 ? 1e9 : 10.0 * std::log10(1.0 / mse);
}

TEST(WorldImport, FindsTheFrameAndTheCutCaptureDrawsLikeTheUncutFile) {
    const fs::path dir = fresh_dir("cut");
    const SplatCloud original = y_down(synthetic_capture());
    splat_lod::write_inria_ply(dir / "capture.ply", original);
    const world::ImportResult result = world::import_world(fast_options(dir / "capture.ply", dir / "world"));
    const world::ImportSummary& s = result.summary;
    EXPECT_EQ(s.up, glm::dvec3(0.0, -1.0, 0.0)) << "the Y-down file's up, snapped to the axis";
    EXPECT_EQ(s.far_huge, 4u) << "the sky Gaussians";
    EXPECT_EQ(s.far_outside, 3u) << "the floaters";
    EXPECT_EQ(s.binned + s.far_layer, original.size());
    EXPECT_GT(result.manifest.chunks.size(), 4u);
    for (const world::ChunkEntry& chunk : result.manifest.chunks) {
        EXPECT_LE(chunk.prefix_count[0], 3u * 2048u) << chunk.id;  // the bake adds a few coarse ones
        const float side = result.manifest.chunk_size_m * static_cast<float>(1 << chunk.span);
        EXPECT_LT(chunk.bounds_max.x - chunk.bounds_min.x, 1.01f * side) << chunk.id;
    }
    ASSERT_EQ(result.manifest.props.size(), 1u) << "the far layer";
    EXPECT_FALSE(result.manifest.ground.empty());

    // The world's finest Gaussians and its far layer, drawn from a view in the world's frame, against the
    // uncut file drawn from the same view taken back into the capture's frame.
    const SplatCloud chunks = splat_lod::read_capture(dir / "world" / world::kManifestFileName);
    const SplatCloud far = splat_lod::load_splat_file(dir / "world" / result.manifest.props[0].mesh);
    EXPECT_EQ(chunks.size() + far.size(), original.size());
    const glm::dmat4 to_world = glm::translate(glm::dmat4(1.0), s.translation) * glm::dmat4(s.rotation);
    const auto camera = engine::make_look_at_camera({25.0f, 18.0f, 30.0f}, {0.0f, 1.0f, 0.0f}, {0, 1, 0}, 1.0f, 160,
                                                    120, 0.2f, 1000.0f);
    splat_lod::reference::ReferenceSettings settings;
    settings.threads = 2;
    const std::vector<splat_lod::reference::ReferenceInstance> imported{{&chunks, glm::dmat4(1.0)},
                                                                        {&far, glm::dmat4(1.0)}};
    const std::vector<splat_lod::reference::ReferenceInstance> uncut{{&original, to_world}};
    const auto a = splat_lod::reference::render_reference(imported, camera, settings);
    const auto b = splat_lod::reference::render_reference(uncut, camera, settings);
    EXPECT_GE(psnr(a, b), 60.0);
}

// The quadtree (ImportOptions::quadtree): a 64 × 64 unit field of sparse ground (one Gaussian per square unit) with a
// dense 4 × 4 patch (6,000) in one corner. The patch sets the grid's cell (4 units: it falls in four cells of 1,500,
// none over 2,048); the sparse ground (16 per cell) is merged into chunks of up to 8 × 8 cells (13 chunks instead of
// 256), each centre inside its chunk's square and every chunk under the group one depth above its span. The cut world
// draws like the uncut file.
TEST(WorldImport, SparseGroundIsCutIntoFewerLargerChunks) {
    const fs::path dir = fresh_dir("quadtree");
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    SplatCloud cloud;
    cloud.resize(4096 + 6000);
    for (std::size_t k = 0; k < cloud.size(); ++k) {
        const bool patch = k >= 4096;
        const glm::vec2 at =
            patch ? glm::vec2(-30.0f + 4.0f * unit(rng), -30.0f + 4.0f * unit(rng))
                  : glm::vec2(-32.0f + static_cast<float>(k % 64) + 0.5f, -32.0f + static_cast<float>(k / 64) + 0.5f);
        cloud.positions[k] = {at.x, 0.05f * unit(rng), at.y};
        cloud.log_scales[k] = {std::log(patch ? 0.05f : 0.4f), std::log(0.01f), std::log(patch ? 0.05f : 0.4f)};
        cloud.opacity_logits[k] = 3.0f;
        cloud.sh_dc[k] = {0.5f * unit(rng), 0.8f * unit(rng), 0.2f};
    }
    splat_lod::write_inria_ply(dir / "capture.ply", cloud);
    world::ImportOptions options = fast_options(dir / "capture.ply", dir / "world");
    options.quadtree = true;
    options.chunk_codec = world::ChunkCodec::ply;  // lossless, so that the render below shows the cut alone
    const world::ImportResult result = world::import_world(options);
    const world::WorldManifest& m = result.manifest;
    const int count = world::chunks_per_side(m);
    EXPECT_EQ(result.summary.binned, cloud.size());
    EXPECT_EQ(m.chunk_size_m, 4.0f);
    EXPECT_GT(result.summary.merged_chunks, 0u);
    EXPECT_GE(result.summary.largest_span, 3);
    EXPECT_EQ(m.chunks.size(), 13u) << "3 chunks of 8 x 8 cells, 3 of 4 x 4, 3 of 2 x 2 and the patch's 4 cells";
    std::set<std::tuple<int, int, int>> groups;
    for (const world::ChunkEntry& g : m.groups) groups.insert({g.depth, g.cell.x, g.cell.y});
    for (const world::ChunkEntry& c : m.chunks) {
        const float side = m.chunk_size_m * static_cast<float>(1 << c.span);
        const glm::vec2 lo = glm::vec2(c.cell) * m.chunk_size_m;
        EXPECT_GE(c.bounds_min.x, lo.x - 1e-3f) << c.id;
        EXPECT_LE(c.bounds_max.x, lo.x + side + 1e-3f) << c.id;
        EXPECT_GE(c.bounds_min.z, lo.y - 1e-3f) << c.id;
        EXPECT_LE(c.bounds_max.z, lo.y + side + 1e-3f) << c.id;
        const glm::ivec2 parent = world::group_of_chunk(c.cell, count, c.span + 1);
        EXPECT_TRUE(groups.count({c.span + 1, parent.x, parent.y})) << c.id << " has no group above it";
    }
    const SplatCloud chunks = splat_lod::read_capture(dir / "world" / world::kManifestFileName);
    EXPECT_EQ(chunks.size(), cloud.size());
    const world::ImportResult grid = world::import_world(fast_options(dir / "capture.ply", dir / "grid"));
    EXPECT_EQ(grid.manifest.chunks.size(), 256u) << "without the quadtree (the default) every cell its own chunk";
    EXPECT_EQ(grid.summary.merged_chunks, 0u);
    const glm::dmat4 to_world =
        glm::translate(glm::dmat4(1.0), result.summary.translation) * glm::dmat4(result.summary.rotation);
    const auto camera = engine::make_look_at_camera({20.0f, 25.0f, 30.0f}, {-10.0f, 0.0f, -10.0f}, {0, 1, 0}, 1.0f, 160,
                                                    120, 0.2f, 1000.0f);
    splat_lod::reference::ReferenceSettings settings;
    settings.threads = 2;
    const std::vector<splat_lod::reference::ReferenceInstance> imported{{&chunks, glm::dmat4(1.0)}},
        uncut{{&cloud, to_world}};
    const auto a = splat_lod::reference::render_reference(imported, camera, settings);
    const auto b = splat_lod::reference::render_reference(uncut, camera, settings);
    EXPECT_GE(psnr(a, b), 60.0);
}

TEST(WorldImport, OutOfCoreUnderATinyCapGivesTheSameBytes) {
    const fs::path dir = fresh_dir("tiny_cap");
    splat_lod::write_inria_ply(dir / "capture.ply", synthetic_capture());
    world::ImportOptions roomy = fast_options(dir / "capture.ply", dir / "roomy");
    world::ImportOptions tiny = fast_options(dir / "capture.ply", dir / "tiny");
    tiny.memory_bytes = std::uint64_t{256} << 20;
    tiny.part_records = 500;          // 16 parts read one at a time
    tiny.bin_flush_bytes = 16 << 10;  // bins written out every 16 KiB
    const auto a = world::import_world(roomy);
    const auto b = world::import_world(tiny);
    ASSERT_EQ(a.manifest.chunks.size(), b.manifest.chunks.size());
    for (std::size_t k = 0; k < a.manifest.chunks.size(); ++k)
        EXPECT_EQ(engine::read_binary_file(dir / "roomy" / a.manifest.chunks[k].file),
                  engine::read_binary_file(dir / "tiny" / b.manifest.chunks[k].file))
            << a.manifest.chunks[k].id;
    EXPECT_GT(b.summary.bin_flushes, 10u);
}

// Every file world.json names, by its path relative to the world's folder (world.json itself included).
std::map<fs::path, std::vector<std::uint8_t>> world_files(const fs::path& folder) {
    std::map<fs::path, std::vector<std::uint8_t>> files;
    const auto m = world::read_world_manifest(folder / world::kManifestFileName);
    files[world::kManifestFileName] = engine::read_binary_file(folder / world::kManifestFileName);
    for (const auto* list : {&m.chunks, &m.groups})
        for (const auto& c : *list) files[c.file] = engine::read_binary_file(folder / c.file);
    for (const auto& p : m.props) files[p.mesh] = engine::read_binary_file(folder / p.mesh);
    return files;
}

TEST(WorldImport, ShardedImportsGiveTheSameBytesAndTheMergeChecksThem) {
    const fs::path dir = fresh_dir("sharded");
    splat_lod::write_inria_ply(dir / "capture.ply", synthetic_capture());
    world::import_world(fast_options(dir / "capture.ply", dir / "whole"));
    const world::ImportOptions o = fast_options(dir / "capture.ply", dir / "sharded");
    const auto first = world::import_world_shard(o, {1, 3});
    EXPECT_TRUE(fs::exists(first.record));
    world::import_world_shard(o, {2, 3});
    const std::string early = error_of([&] { world::merge_import_shards(o); });
    EXPECT_NE(early.find("missing shards 3/3"), std::string::npos) << early;
    EXPECT_FALSE(fs::exists(dir / "sharded" / world::kManifestFileName));

    const auto third = world::import_world_shard(o, {3, 3});
    ASSERT_FALSE(third.manifest.chunks.empty());
    const fs::path staged = third.record.parent_path() / third.manifest.chunks.front().file;
    const auto bytes = engine::read_binary_file(staged);
    auto broken = bytes;
    broken[broken.size() / 2] ^= 0x40;
    engine::write_file_atomic(staged, broken);
    const std::string tampered = error_of([&] { world::merge_import_shards(o); });
    EXPECT_NE(tampered.find(staged.filename().string()), std::string::npos) << tampered;
    EXPECT_FALSE(fs::exists(dir / "sharded" / world::kManifestFileName));
    EXPECT_FALSE(world::import_world_shard(o, {3, 3}).summary.cached) << "a record its files do not match is rebaked";

    const auto merged = world::merge_import_shards(o);
    EXPECT_FALSE(merged.summary.cached);
    EXPECT_EQ(world_files(dir / "sharded"), world_files(dir / "whole"));
    EXPECT_FALSE(fs::exists(first.record.parent_path())) << "the staging folder goes with the merge";
    EXPECT_TRUE(world::import_world_shard(o, {2, 3}).summary.cached) << "the folder's world is this import";
}

// 30 cameras 15 units above the patch looking down and a little north, as cameras.json in the frame of
// the capture y_down() and moved 200 units along x: the import must move and turn them with the capture
// for them to see anything.
std::string training_cameras_json() {
    const glm::dmat3 turn = splat_lod::rotation_between({0, 1, 0}, {0, -1, 0});
    std::string text = "[";
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 5; ++j) {
            const glm::dvec3 eye(-17.5 + 7.0 * i, 15.0, -12.0 + 6.0 * j);
            const glm::dvec3 forward = glm::normalize(glm::dvec3(0.0, -1.0, -0.2));
            const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
            const glm::dvec3 down = glm::cross(forward, right);
            const glm::dmat3 c2w = turn * glm::dmat3(right, down, forward);
            const glm::dvec3 p = turn * eye + glm::dvec3(200.0, 0.0, 0.0);
            char camera[512];
            std::snprintf(camera, sizeof camera,
                          R"(%s{"id": %d, "img_name": "c%d", "width": 500, "height": 500, "fx": 500, "fy": 500, )"
                          R"("position": [%.9g, %.9g, %.9g], "rotation": [[%.9g, %.9g, %.9g], [%.9g, %.9g, %.9g], )"
                          R"([%.9g, %.9g, %.9g]]})",
                          text.size() > 1 ? ", " : "", 5 * i + j, 5 * i + j, p.x, p.y, p.z, c2w[0][0], c2w[1][0],
                          c2w[2][0], c2w[0][1], c2w[1][1], c2w[2][1], c2w[0][2], c2w[1][2], c2w[2][2]);
            text += camera;
        }
    return text + "]";
}

TEST(WorldImport, TrainingCamerasTurnWithTheCaptureAndBakeTheChunksTheySee) {
    const fs::path dir = fresh_dir("training_cameras");
    SplatCloud capture = y_down(synthetic_capture());
    splat_lod::transform_cloud(capture, glm::dmat3(1.0), glm::dvec3(200.0, 0.0, 0.0));
    splat_lod::write_inria_ply(dir / "capture.ply", capture);
    engine::write_text_file_atomic(dir / "cameras.json", training_cameras_json());
    world::ImportOptions o = fast_options(dir / "capture.ply", dir / "world");
    o.cameras = dir / "cameras.json";
    const auto with = world::import_world(o);
    EXPECT_EQ(with.summary.training_cameras, 30u);
    EXPECT_GT(with.summary.training_camera_chunks, with.manifest.chunks.size() / 2)
        << "most chunks lie under the cameras; none would, were the cameras not turned with the capture";
    EXPECT_NE(world::format_import_summary(with.summary).find("training cameras: 30 read"), std::string::npos);
    o.cameras.clear();
    const auto without = world::import_world(o);
    EXPECT_FALSE(without.summary.cached) << "the cameras are part of the fingerprint";
    EXPECT_EQ(without.summary.training_camera_chunks, 0u);
    o.cameras = dir / "missing.json";
    EXPECT_NE(error_of([&] { world::import_world(o); }).find("missing.json"), std::string::npos);
}

TEST(WorldImport, TheSameCaptureAndOptionsAreNotImportedTwice) {
    const fs::path dir = fresh_dir("cached");
    splat_lod::write_inria_ply(dir / "capture.ply", synthetic_capture());
    world::ImportOptions o = fast_options(dir / "capture.ply", dir / "world");
    const auto first = world::import_world(o);
    EXPECT_FALSE(first.summary.cached);
    const auto second = world::import_world(o);
    EXPECT_TRUE(second.summary.cached);
    EXPECT_EQ(second.manifest.chunks.size(), first.manifest.chunks.size());
    o.max_chunk_gaussians = 4096;  // another option: imported again
    EXPECT_FALSE(world::import_world(o).summary.cached);
    splat_lod::write_inria_ply(dir / "capture.ply", y_down(synthetic_capture()));  // another file
    EXPECT_FALSE(world::import_world(o).summary.cached);
    o.force = true;
    EXPECT_FALSE(world::import_world(o).summary.cached);
}

TEST(WorldImport, FindsZUpAndCountsHostileGaussians) {
    const fs::path dir = fresh_dir("hostile");
    SplatCloud cloud = synthetic_capture();
    splat_lod::transform_cloud(cloud, splat_lod::rotation_between({0, 1, 0}, {0, 0, 1}), glm::dvec3(100.0, 5.0, -3.0));
    const std::size_t n = cloud.size();
    cloud.resize(n + 3);
    cloud.log_scales[n] = glm::vec3(-40.0f);  // zero scale
    cloud.opacity_logits[n] = 2.0f;
    cloud.opacity_logits[n + 1] = -20.0f;  // never visible
    cloud.positions[n + 2] = {NAN, 0.0f, 0.0f};
    splat_lod::write_inria_ply(dir / "capture.ply", cloud);
    const auto result = world::import_world(fast_options(dir / "capture.ply", dir / "world"));
    EXPECT_EQ(result.summary.up, glm::dvec3(0.0, 0.0, 1.0));
    EXPECT_EQ(result.summary.dropped_by_reader, 1u);
    EXPECT_EQ(result.summary.degenerate, 1u);
    EXPECT_EQ(result.summary.invisible, 1u);
    EXPECT_EQ(result.summary.binned + result.summary.far_layer, n);
}

TEST(WorldImport, NormalsSpreadOverEveryDirectionGiveWayToTheThinnestAxis) {
    // 4,000 flat, opaque Gaussians turned every which way (leaves, litter: no ground facing up) in a
    // 30 x 30 patch, most near the ground and a tail up to 6 units: their normals say nothing.
    const fs::path dir = fresh_dir("spread_normals");
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    SplatCloud cloud;
    cloud.resize(4000);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const float h = unit(rng);
        cloud.positions[i] = {30.0f * unit(rng) - 15.0f, 6.0f * h * h * h, 30.0f * unit(rng) - 15.0f};
        cloud.log_scales[i] = {std::log(0.1f), std::log(0.005f), std::log(0.1f)};
        const glm::vec4 q = glm::normalize(glm::vec4(gauss(rng), gauss(rng), gauss(rng), gauss(rng)));
        cloud.rotations[i] = {q.x, q.y, q.z, q.w};
        cloud.opacity_logits[i] = 3.0f;
    }
    splat_lod::write_inria_ply(dir / "capture.ply", cloud);
    const auto result = world::import_world(fast_options(dir / "capture.ply", dir / "world"));
    EXPECT_EQ(result.summary.up, glm::dvec3(0.0, 1.0, 0.0));
    EXPECT_NE(result.summary.up_source.find("ambiguous"), std::string::npos) << result.summary.up_source;
}

TEST(WorldImport, ACaptureDenserThanAnyChunkKeepsTheGridBounded) {
    const fs::path dir = fresh_dir("dense_spot");
    // 3,000 ground Gaussians on one spot and 300 of the leaves spread over the patch: the spot holds more
    // than any chunk may at every chunk size.
    const SplatCloud patch = synthetic_capture();
    std::vector<std::uint32_t> kept;
    for (std::uint32_t i = 0; i < 3000; ++i) kept.push_back(i);
    for (std::uint32_t i = 6000; i < 6300; ++i) kept.push_back(i);
    SplatCloud cloud = patch.permuted(kept);
    for (std::size_t i = 0; i < 3000; ++i) cloud.positions[i] = {3.0f, 0.02f, 2.0f};
    splat_lod::write_inria_ply(dir / "capture.ply", cloud);
    const auto result = world::import_world(fast_options(dir / "capture.ply", dir / "world"));
    const float per_side = result.manifest.size_m / result.manifest.chunk_size_m;
    EXPECT_LE(per_side, 1024.0f);
    EXPECT_GT(per_side, 64.0f) << "it did split as far as the grid allows";
    EXPECT_GT(result.summary.unbaked_chunks, 0u) << "chunks of stray leaves far above the ground grid";
    EXPECT_LT(result.summary.unbaked_chunks, result.manifest.chunks.size());
    EXPECT_EQ(result.summary.binned + result.summary.far_layer, cloud.size());
}

TEST(WorldImport, HopelessCapturesAreRefusedAndKeepThePreviousWorld) {
    const fs::path dir = fresh_dir("refused");
    splat_lod::write_inria_ply(dir / "good.ply", synthetic_capture());
    world::import_world(fast_options(dir / "good.ply", dir / "world"));
    const std::string manifest = engine::read_text_file(dir / "world" / world::kManifestFileName);

    SplatCloud point = synthetic_capture();
    for (auto& p : point.positions) p = glm::vec3(1.0f, 2.0f, 3.0f);
    splat_lod::write_inria_ply(dir / "point.ply", point);
    SplatCloud giant;
    giant.resize(1);
    giant.log_scales[0] = glm::vec3(6.0f);
    splat_lod::write_inria_ply(dir / "giant.ply", giant);
    SplatCloud empty;
    splat_lod::write_inria_ply(dir / "empty.ply", empty);
    splat_lod::write_inria_ply(dir / "cut.ply", synthetic_capture());
    fs::resize_file(dir / "cut.ply", fs::file_size(dir / "cut.ply") / 2);
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"point.ply", "no horizontal extent"},
        {"giant.ply", "no horizontal extent"},
        {"empty.ply", "no visible Gaussian"},
        {"cut.ply", "cut.ply"},
    };
    for (const auto& [file, expected] : cases) {
        const std::string message = error_of([&] { world::import_world(fast_options(dir / file, dir / "world")); });
        EXPECT_NE(message.find(expected), std::string::npos) << file << ": " << message;
        EXPECT_EQ(engine::read_text_file(dir / "world" / world::kManifestFileName), manifest) << file;
    }
    const auto m = world::read_world_manifest(dir / "world" / world::kManifestFileName);
    for (const auto& chunk : m.chunks) EXPECT_TRUE(fs::exists(dir / "world" / chunk.file)) << chunk.id;
}

}  // namespace
