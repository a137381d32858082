// Chunk groups (splat_lod/worldgen/world_groups.h): the quadtree's indices, the pooling of a cell by
// moment matching against closed forms, cells that a chunk border does not cut, and the groups of a
// generated tiny world (built with it, rebuilt alone when only their settings change).
#include <cmath>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/worldgen/world_generator.h"
#include "splat_lod/worldgen/world_groups.h"
#include "test_support.h"
#include "tiny_world.h"

namespace sw = splat_lod::world;
using splat_lod::SplatCloud;

namespace {

double sigmoid(double x) {
    return 1.0 / (1.0 + std::exp(-x));
}

// One axis-aligned Gaussian: mean p, standard deviations s, opacity a, DC colour c, level 1.
void add(SplatCloud& cloud, glm::vec3 p, glm::vec3 s, double a, glm::vec3 c, std::uint8_t level = 1) {
    const std::size_t i = cloud.size();
    cloud.resize(i + 1);
    cloud.positions[i] = p;
    cloud.log_scales[i] = glm::log(s);
    cloud.opacity_logits[i] = static_cast<float>(std::log(a / (1.0 - a)));
    cloud.sh_dc[i] = c;
    cloud.lod_level[i] = level;
}

glm::dmat3 covariance(const SplatCloud& c, std::size_t i) {
    const auto& q = c.rotations[i];
    const glm::dmat3 r = glm::mat3_cast(glm::dquat(q.w, q.x, q.y, q.z));
    const glm::dvec3 s = glm::exp(glm::dvec3(c.log_scales[i]));
    const glm::dmat3 rs = r * glm::dmat3(s.x, 0, 0, 0, s.y, 0, 0, 0, s.z);
    return rs * glm::transpose(rs);
}

double area(const glm::dmat3& s) {
    const double xy = s[0][0] * s[1][1] - s[1][0] * s[1][0];
    const double xz = s[0][0] * s[2][2] - s[2][0] * s[2][0];
    const double yz = s[1][1] * s[2][2] - s[2][1] * s[2][1];
    return (std::sqrt(xy) + std::sqrt(xz) + std::sqrt(yz)) / 3.0;
}

void expect_near(const glm::dmat3& a, const glm::dmat3& b, double tolerance) {
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(a[c][r], b[c][r], tolerance) << "[" << c << "][" << r << "]";
}

}  // namespace

TEST(WorldGroups, QuadtreeIndices) {
    EXPECT_EQ(sw::group_depths(1), 0);
    EXPECT_EQ(sw::group_depths(2), 1);
    EXPECT_EQ(sw::group_depths(3), 2);
    EXPECT_EQ(sw::group_depths(16), 4);
    // 16 chunks per side: cells −8 … 7; depth 1 pairs them from the world's corner.
    EXPECT_EQ(sw::group_of_chunk({-8, -8}, 16, 1), glm::ivec2(0, 0));
    EXPECT_EQ(sw::group_of_chunk({-7, 7}, 16, 1), glm::ivec2(0, 7));
    EXPECT_EQ(sw::group_of_chunk({7, -1}, 16, 4), glm::ivec2(0, 0));
    EXPECT_EQ(sw::group_of_chunk({1, 1}, 3, 1), glm::ivec2(1, 1));  // odd grids: cells −1 … 1
    EXPECT_EQ(sw::group_id(2, {1, 3}), "group_2_+001_+003");
    const sw::GroupOptions options;
    EXPECT_EQ(sw::group_cell_size(options, 1), 1.0f);
    EXPECT_EQ(sw::group_cell_size(options, 4), 8.0f);
    EXPECT_EQ(sw::check_group_options(options, 64.0f), "");
    EXPECT_NE(sw::check_group_options({true, 0.3f}, 64.0f), "");
    EXPECT_NE(sw::check_group_options({true, -1.0f}, 64.0f), "");
}

TEST(WorldGroups, OneMemberIsKeptAsItIs) {
    SplatCloud cloud;
    add(cloud, {0.3f, 0.2f, 0.1f}, {0.05f, 0.02f, 0.01f}, 0.7, {0.1f, 0.2f, 0.3f});
    const SplatCloud out = sw::pool_group(std::vector<SplatCloud>{cloud}, glm::vec3(0.0f), 1.0f);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_NEAR(glm::distance(out.positions[0], cloud.positions[0]), 0.0f, 1e-6f);
    expect_near(covariance(out, 0), covariance(cloud, 0), 1e-9);
    EXPECT_NEAR(sigmoid(out.opacity_logits[0]), 0.7, 1e-5);
    EXPECT_NEAR(glm::distance(out.sh_dc[0], cloud.sh_dc[0]), 0.0f, 1e-6f);
    EXPECT_EQ(out.lod_level[0], 4);
    EXPECT_EQ(out.coverage_min[0], -1.0f);
    EXPECT_EQ(out.coverage_max[0], -1.0f);
}

TEST(WorldGroups, MomentsOfACell) {
    SplatCloud cloud;
    add(cloud, {0.2f, 0.5f, 0.5f}, {0.04f, 0.04f, 0.04f}, 0.9, {1.0f, 0.0f, 0.0f});
    add(cloud, {0.8f, 0.5f, 0.5f}, {0.08f, 0.02f, 0.04f}, 0.3, {0.0f, 1.0f, 0.0f});
    const SplatCloud out = sw::pool_group(std::vector<SplatCloud>{cloud}, glm::vec3(0.0f), 1.0f);
    ASSERT_EQ(out.size(), 1u);
    const double w0 = 0.9 * area(covariance(cloud, 0)), w1 = 0.3 * area(covariance(cloud, 1));
    const double f0 = w0 / (w0 + w1), f1 = w1 / (w0 + w1);
    const glm::dvec3 m0(cloud.positions[0]), m1(cloud.positions[1]);
    const glm::dvec3 mean = f0 * m0 + f1 * m1;
    EXPECT_NEAR(glm::distance(glm::dvec3(out.positions[0]), mean), 0.0, 1e-6);
    const glm::dmat3 expected = f0 * (covariance(cloud, 0) + glm::outerProduct(m0 - mean, m0 - mean)) +
                                f1 * (covariance(cloud, 1) + glm::outerProduct(m1 - mean, m1 - mean));
    expect_near(covariance(out, 0), expected, 1e-7);
    const double a = area(expected);
    const double opacity =
        1.0 - (1.0 - 0.9 * area(covariance(cloud, 0)) / a) * (1.0 - 0.3 * area(covariance(cloud, 1)) / a);
    EXPECT_NEAR(sigmoid(out.opacity_logits[0]), opacity, 1e-5);
    EXPECT_NEAR(out.sh_dc[0].x, f0, 1e-5);
    EXPECT_NEAR(out.sh_dc[0].y, f1, 1e-5);
}

TEST(WorldGroups, ChunkBordersDoNotCutCells) {
    // Four Gaussians in the cell [2, 4)³, split between two "chunks" at x = 3: the group pools them
    // into one Gaussian, exactly as if one chunk held them all.
    SplatCloud left, right, both;
    const glm::vec3 a{2.5f, 3.0f, 3.0f}, b{2.9f, 3.5f, 2.5f}, c{3.1f, 2.5f, 3.5f}, d{3.7f, 3.2f, 2.2f};
    add(left, a, glm::vec3(0.1f), 0.5, {1, 0, 0});
    add(left, b, glm::vec3(0.2f), 0.6, {0, 1, 0});
    add(right, c, glm::vec3(0.1f), 0.7, {0, 0, 1});
    add(right, d, glm::vec3(0.3f), 0.8, {1, 1, 0});
    for (const SplatCloud* part : {&left, &right})
        for (std::size_t i = 0; i < part->size(); ++i)
            add(both, part->positions[i], glm::exp(part->log_scales[i]), sigmoid(part->opacity_logits[i]),
                part->sh_dc[i]);
    const SplatCloud split = sw::pool_group(std::vector<SplatCloud>{left, right}, glm::vec3(0.0f), 2.0f);
    const SplatCloud whole = sw::pool_group(std::vector<SplatCloud>{both}, glm::vec3(0.0f), 2.0f);
    ASSERT_EQ(split.size(), 1u);
    ASSERT_EQ(whole.size(), 1u);
    EXPECT_NEAR(glm::distance(split.positions[0], whole.positions[0]), 0.0f, 1e-6f);
    expect_near(covariance(split, 0), covariance(whole, 0), 1e-7);
    EXPECT_NEAR(split.opacity_logits[0], whole.opacity_logits[0], 1e-5f);
    // Shifted by a cell boundary at x = 3 instead (origin 1): two cells, two Gaussians.
    EXPECT_EQ(sw::pool_group(std::vector<SplatCloud>{left, right}, glm::vec3(1.0f, 0.0f, 0.0f), 2.0f).size(), 2u);
}

// A group reads its members when it needs them, one at a time and twice each, in order (what lets a
// group of a whole world pool in the memory of one chunk), and pools them to the same bytes as one
// member holding them all in the same order: every sum runs in the same order.
TEST(WorldGroups, MembersAreReadOneAtATimeTwiceInOrderToTheSameBytes) {
    std::vector<SplatCloud> members(3);
    SplatCloud all;
    for (std::size_t m = 0; m < members.size(); ++m)
        for (int k = 0; k < 40; ++k) {
            const float t = static_cast<float>(m * 40 + static_cast<std::size_t>(k));
            const glm::vec3 p(std::fmod(t * 0.37f, 5.0f), std::fmod(t * 0.61f, 3.0f), std::fmod(t * 0.23f, 4.0f));
            const glm::vec3 s(k % 9 == 0 ? 1.5f : 0.05f + 0.01f * static_cast<float>(k % 5));  // some kept
            const glm::vec3 c(0.1f * static_cast<float>(k % 7), 0.5f, 0.05f * static_cast<float>(m));
            add(members[m], p, s, 0.3 + 0.01 * k, c);
            add(all, p, s, 0.3 + 0.01 * k, c);
        }
    std::vector<std::size_t> reads;
    const auto read = [&](std::size_t m) {
        reads.push_back(m);
        return members[m];
    };
    const SplatCloud streamed = sw::pool_group(members.size(), read, glm::vec3(0.0f), 1.0f, 1.5f);
    const SplatCloud whole = sw::pool_group(std::vector<SplatCloud>{all}, glm::vec3(0.0f), 1.0f, 1.5f);
    EXPECT_EQ(reads, (std::vector<std::size_t>{0, 1, 2, 0, 1, 2}));
    ASSERT_EQ(streamed.size(), whole.size());
    EXPECT_GT(streamed.size(), 20u);
    for (std::size_t i = 0; i < whole.size(); ++i) {
        EXPECT_EQ(streamed.positions[i], whole.positions[i]) << i;
        EXPECT_EQ(streamed.log_scales[i], whole.log_scales[i]) << i;
        EXPECT_EQ(streamed.opacity_logits[i], whole.opacity_logits[i]) << i;
        EXPECT_EQ(streamed.sh_dc[i], whole.sh_dc[i]) << i;
        EXPECT_EQ(streamed.rotations[i].w, whole.rotations[i].w) << i;
    }
}

TEST(WorldGroups, LargeKeptCoarseAndBadLeftOut) {
    SplatCloud cloud;
    add(cloud, {0.5f, 0.5f, 0.5f}, {2.0f, 0.1f, 2.0f}, 0.9, {0.5f, 0.5f, 0.5f});  // larger than the cell: kept
    add(cloud, {0.4f, 0.4f, 0.4f}, glm::vec3(0.05f), 0.9, {1, 0, 0});
    add(cloud, {0.6f, 0.6f, 0.6f}, glm::vec3(0.05f), 0.9, {1, 0, 0});
    add(cloud, {0.5f, 0.5f, 0.5f}, glm::vec3(0.05f), 0.9, {0, 0, 1}, 3);  // a coarse level: not pooled
    add(cloud, {0.5f, 0.5f, 0.5f}, glm::vec3(0.05f), 0.001, {0, 0, 1});   // below 1/255: invisible
    add(cloud, {0.5f, 0.5f, 0.5f}, glm::vec3(0.05f), 0.9, {0, 0, 1});
    cloud.positions.back().x = std::nanf("");
    const SplatCloud out = sw::pool_group(std::vector<SplatCloud>{cloud}, glm::vec3(0.0f), 1.0f);
    ASSERT_EQ(out.size(), 2u);  // the pooled pair, then the kept one
    EXPECT_NEAR(out.sh_dc[0].x, 1.0f, 1e-6f);
    EXPECT_EQ(out.positions[1], cloud.positions[0]);
    EXPECT_EQ(out.log_scales[1], cloud.log_scales[0]);
    EXPECT_TRUE(sw::pool_group(std::vector<SplatCloud>{}, glm::vec3(0.0f), 1.0f).empty());
}

TEST(WorldGroups, TinyWorldHasGroupsAndRebuildsThemAlone) {
    const auto folder = engine::test::output_dir("world_groups") / "tiny";
    std::filesystem::remove_all(folder);
    sw::WorldOptions options = engine::test::tiny_world_options(folder);
    const sw::WorldResult first = sw::generate_world(options);
    const sw::WorldManifest& m = first.manifest;
    // 3 × 3 chunks: 2 × 2 groups of depth 1, one root of depth 2.
    ASSERT_EQ(m.groups.size(), 5u);
    EXPECT_EQ(m.group_generator, sw::group_generator_settings(options.groups));
    std::uint64_t fine = 0, pooled_root = 0;
    for (const auto& c : m.chunks) {
        const SplatCloud cloud = sw::read_chunk_range(folder / c.file, c, 0, c.prefix_count[0]);
        for (const auto level : cloud.lod_level) fine += level == 1 ? 1 : 0;
    }
    for (const auto& g : m.groups) {
        EXPECT_EQ(g.cell_m, sw::group_cell_size(options.groups, g.depth)) << g.id;
        EXPECT_EQ(g.prefix_count[3], g.prefix_count[0]) << g.id;
        const SplatCloud cloud = sw::read_chunk_range(folder / g.file, g, 0, g.prefix_count[0]);
        for (const auto level : cloud.lod_level) EXPECT_EQ(level, 4);
        if (g.depth == 2) pooled_root = cloud.size();
    }
    EXPECT_GT(pooled_root, 0u);
    EXPECT_LT(pooled_root * 2, fine) << "the root pools the whole world into far fewer Gaussians";
    const auto reread = sw::read_world_manifest(folder / sw::kManifestFileName);
    EXPECT_EQ(reread.groups.size(), 5u);

    // Other group settings: the same chunk files stay, only the groups are new.
    options.groups.base_cell_m = 2.0f;
    const sw::WorldResult second = sw::generate_world(options);
    EXPECT_TRUE(second.summary.cached);
    EXPECT_TRUE(second.summary.groups_rebuilt);
    ASSERT_EQ(second.manifest.chunks.size(), m.chunks.size());
    for (std::size_t k = 0; k < m.chunks.size(); ++k) EXPECT_EQ(second.manifest.chunks[k].file, m.chunks[k].file);
    ASSERT_EQ(second.manifest.groups.size(), 5u);
    EXPECT_NE(second.manifest.groups[0].file.begin()->string(), m.groups[0].file.begin()->string());
    EXPECT_FALSE(std::filesystem::exists(folder / m.groups[0].file)) << "the old groups are removed";
    for (const auto& g : second.manifest.groups) EXPECT_TRUE(std::filesystem::exists(folder / g.file)) << g.id;
    const sw::WorldResult third = sw::generate_world(options);
    EXPECT_TRUE(third.summary.cached);
    EXPECT_FALSE(third.summary.groups_rebuilt);
}

TEST(WorldGroups, FillWidensTheSpreadAxesAndKeepsTheCoveredArea) {
    SplatCloud cloud;
    add(cloud, {0.3f, 0.5f, 0.5f}, {0.1f, 0.001f, 0.15f}, 0.4, {1, 0, 0});  // flat in y: that axis stays thin
    add(cloud, {0.7f, 0.5f, 0.5f}, {0.1f, 0.001f, 0.15f}, 0.4, {1, 0, 0});
    const std::vector<SplatCloud> members{cloud};
    const SplatCloud plain = sw::pool_group(members, glm::vec3(0.0f), 1.0f, 1.0f);
    const SplatCloud filled = sw::pool_group(members, glm::vec3(0.0f), 1.0f, 2.0f);
    ASSERT_EQ(plain.size(), 1u);
    ASSERT_EQ(filled.size(), 1u);
    const glm::dmat3 a = covariance(plain, 0), b = covariance(filled, 0);
    EXPECT_NEAR(b[0][0], 4.0 * a[0][0], 1e-6);
    EXPECT_NEAR(b[2][2], 4.0 * a[2][2], 1e-6);
    EXPECT_NEAR(b[1][1], a[1][1], 1e-9) << "the thin axis is not widened";
    // Each member covers less of the wider Gaussian: α·A of the two members, spread over 4× the area.
    const double member = 0.4 * area(covariance(cloud, 0));
    const double expected = 1.0 - std::pow(1.0 - member / area(b), 2.0);
    EXPECT_NEAR(sigmoid(filled.opacity_logits[0]), expected, 1e-5);
    EXPECT_LT(sigmoid(filled.opacity_logits[0]), sigmoid(plain.opacity_logits[0]));
}
