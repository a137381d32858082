// The procedural fine-detail scene and its builders: reproducible bytes, the documented counts
// and sizes, the fence's board pitch, no holes in the ground, and a PLY that loads back.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "engine/core/error.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/synth/fine_detail_scene.h"
#include "test_support.h"

using splat_lod::SplatCloud;
namespace synth = splat_lod::synth;

namespace {

// The detail-1 scene, built once for the tests that only read it.
const SplatCloud& full_scene() {
    static const SplatCloud cloud = synth::make_fine_detail_scene({});
    return cloud;
}

std::vector<char> file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

float largest_scale(const glm::vec3& log_scale) {
    return std::exp(std::max({log_scale.x, log_scale.y, log_scale.z}));
}

float smallest_scale(const glm::vec3& log_scale) {
    return std::exp(std::min({log_scale.x, log_scale.y, log_scale.z}));
}

// Column k of the Gaussian's rotation matrix (its k-th local axis), as in 3DGS.
glm::vec3 local_axis(const splat_lod::Rotation& q, int k) {
    const float w = q.w, x = q.x, y = q.y, z = q.z;
    if (k == 0) return {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
    if (k == 1) return {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
    return {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
}

using splat_io_test::error_of;  // the engine::Error message, "" when none

}  // namespace

TEST(FineDetailScene, SameSeedWritesIdenticalBytesAndAnotherSeedDiffers) {
    const auto dir = engine::test::output_dir("synth");
    // A reduced detail keeps this fast; every builder and every random stream still runs.
    const synth::FineDetailOptions options{7, 0.3f};
    splat_lod::write_inria_ply(dir / "first.ply", synth::make_fine_detail_scene(options));
    splat_lod::write_inria_ply(dir / "second.ply", synth::make_fine_detail_scene(options));
    splat_lod::write_inria_ply(dir / "other_seed.ply", synth::make_fine_detail_scene({8, 0.3f}));
    const auto first = file_bytes(dir / "first.ply");
    ASSERT_GT(first.size(), 1000u);
    EXPECT_TRUE(first == file_bytes(dir / "second.ply"));
    EXPECT_FALSE(first == file_bytes(dir / "other_seed.ply"));
}

TEST(FineDetailScene, CountIsInTheDocumentedRangeAndFallsWithDetail) {
    const std::size_t full = full_scene().size();
    EXPECT_GE(full, synth::kFineDetailGaussiansMin);
    EXPECT_LE(full, synth::kFineDetailGaussiansMax);
    const std::size_t half = synth::make_fine_detail_scene({1, 0.5f}).size();
    EXPECT_LT(half, full);
    // Roughly proportional: every builder scales its count with detail.
    EXPECT_NEAR(static_cast<double>(half) / static_cast<double>(full), 0.5, 0.1);
}

TEST(FineDetailScene, EveryAttributeIsFiniteAndEveryQuaternionUnit) {
    const SplatCloud& cloud = full_scene();
    ASSERT_NO_THROW(cloud.check_consistent());
    EXPECT_EQ(cloud.sh_degree, 0);
    EXPECT_FALSE(cloud.has_lod_attributes());
    EXPECT_TRUE(cloud.extras.empty());
    std::size_t failures = 0;
    for (std::size_t i = 0; i < cloud.size() && failures < 10; ++i) {
        const auto& p = cloud.positions[i];
        const auto& s = cloud.log_scales[i];
        const auto& c = cloud.sh_dc[i];
        const auto& q = cloud.rotations[i];
        const bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(s.x) &&
                            std::isfinite(s.y) && std::isfinite(s.z) && std::isfinite(c.x) && std::isfinite(c.y) &&
                            std::isfinite(c.z) && std::isfinite(cloud.opacity_logits[i]);
        const float norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
        // Inside the garden: 5 m ground radius, trees up to 6.3 m.
        const bool inside = std::abs(p.x) < 5.5f && std::abs(p.z) < 5.5f && p.y > -0.1f && p.y < 7.0f;
        if (!finite || std::abs(norm - 1.0f) > 1e-5f || !inside) {
            ADD_FAILURE() << "Gaussian " << i << ": finite " << finite << ", |q| " << norm << ", position (" << p.x
                          << ", " << p.y << ", " << p.z << ")";
            ++failures;
        }
        // Colours come from rgb in [0, 1].
        EXPECT_LE(std::abs(c.x * splat_lod::kShC0), 0.5f + 1e-6f) << i;
    }
}

TEST(FineDetailScene, WrittenFileLoadsBackWithTheSameCount) {
    const auto path = engine::test::output_dir("synth") / "fine_detail.ply";
    splat_lod::write_inria_ply(path, full_scene());
    splat_lod::LoadReport report;
    const SplatCloud loaded = splat_lod::load_splat_file(path, &report);
    EXPECT_EQ(loaded.size(), full_scene().size());
    EXPECT_EQ(report.dropped(), 0u);
    EXPECT_EQ(loaded.sh_degree, 0);
    EXPECT_FALSE(loaded.has_lod_attributes());
    EXPECT_EQ(loaded.positions, full_scene().positions);
}

TEST(FineDetailBuilders, TreeLeavesAreSmallFlatAndOpaqueAtEveryDetail) {
    for (const auto kind : {synth::TreeKind::broadleaf, synth::TreeKind::conifer}) {
        for (const float detail : {0.2f, 1.0f, 4.0f}) {
            SCOPED_TRACE(std::string(kind == synth::TreeKind::conifer ? "conifer" : "broadleaf") + ", detail " +
                         std::to_string(detail));
            SplatCloud cloud;
            synth::Rng rng(3);
            synth::TreeStyle style;
            style.kind = kind;
            style.detail = detail;
            const auto tree = synth::append_tree(cloud, glm::vec3(1.0f, 0.0f, 2.0f), 4.0f, rng, style);
            EXPECT_EQ(tree.bark.begin, 0u);
            EXPECT_GT(tree.bark.size(), 0u);
            EXPECT_EQ(tree.leaves.begin, tree.bark.end);
            EXPECT_EQ(tree.leaves.end, cloud.size());
            if (detail == 1.0f) {
                EXPECT_GT(tree.leaves.size(), 3000u) << "several thousand leaves per tree";
            }
            for (std::size_t i = tree.leaves.begin; i < tree.leaves.end; ++i) {
                const float longest = largest_scale(cloud.log_scales[i]);
                ASSERT_GE(longest, synth::kLeafScaleMin * 0.9999f) << i;
                ASSERT_LE(longest, synth::kLeafScaleMax * 1.0001f) << i;
                ASSERT_NEAR(smallest_scale(cloud.log_scales[i]) / longest, 0.1f, 1e-3f) << i;
                ASSERT_GE(cloud.opacity_logits[i], synth::kLeafOpacityLogitMin) << i;
                ASSERT_LE(cloud.opacity_logits[i], synth::kLeafOpacityLogitMax) << i;
                // Within the crown: above the ground and no higher than the tree plus a leaf.
                ASSERT_GT(cloud.positions[i].y, 0.0f) << i;
                ASSERT_LT(cloud.positions[i].y, 4.0f * 1.05f) << i;
            }
        }
    }
}

TEST(FineDetailBuilders, PicketFenceHasTheDocumentedBoardPitch) {
    SplatCloud cloud;
    synth::Rng rng(5);
    const float height = 1.0f;
    const auto fence = synth::append_picket_fence(cloud, glm::vec3(0.0f), glm::vec3(4.0f, 0.0f, 0.0f), height, rng);
    EXPECT_EQ(fence.board_count, 25);  // floor((4 − 0.08) / 0.16) + 1
    EXPECT_EQ(fence.rails.begin, fence.boards.end);
    EXPECT_EQ(fence.rails.end, cloud.size());
    // Rails sit on the side of up × direction = −z, behind the boards.
    for (std::size_t i = fence.rails.begin; i < fence.rails.end; ++i) ASSERT_LT(cloud.positions[i].z, -0.01f) << i;

    // Cluster the x positions of everything between the rails, where only boards are, into boards.
    std::vector<float> xs;
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (cloud.positions[i].y > 0.35f && cloud.positions[i].y < 0.65f) xs.push_back(cloud.positions[i].x);
    std::sort(xs.begin(), xs.end());
    ASSERT_FALSE(xs.empty());
    struct Board {
        float lo, hi;
    };
    std::vector<Board> boards{{xs.front(), xs.front()}};
    for (const float x : xs) {
        if (x - boards.back().hi > 0.04f) boards.push_back({x, x});
        boards.back().hi = x;
    }
    ASSERT_EQ(boards.size(), 25u);
    for (std::size_t b = 0; b < boards.size(); ++b) {
        // Tile centres span the board width less one tile.
        EXPECT_LE(boards[b].hi - boards[b].lo, synth::kPicketBoardWidth) << b;
        if (b == 0) continue;
        const float pitch = 0.5f * (boards[b].lo + boards[b].hi) - 0.5f * (boards[b - 1].lo + boards[b - 1].hi);
        EXPECT_NEAR(pitch, synth::kPicketPitch, 1e-4f) << b;
    }
    // Centred on the fence line.
    EXPECT_NEAR(0.5f * (boards.front().lo + boards.back().hi), 2.0f, 1e-4f);
}

TEST(FineDetailBuilders, GroundCoversItsDiscWithoutHoles) {
    for (const float detail : {0.25f, 1.0f}) {
        SCOPED_TRACE("detail " + std::to_string(detail));
        SplatCloud cloud;
        synth::Rng rng(11);
        synth::append_ground(cloud, glm::vec3(0.0f), 0.6f, rng, detail);
        // Transmittance straight down at a grid of points inside the disc: every Gaussian is
        // flat with its thin axis vertical, so its footprint is the Gaussian of local axes 0 and 2.
        float worst = 0.0f;
        for (float x = -0.4f; x <= 0.4f; x += 0.013f) {
            for (float z = -0.4f; z <= 0.4f; z += 0.013f) {
                if (x * x + z * z > 0.16f) continue;
                float transmittance = 1.0f;
                for (std::size_t i = 0; i < cloud.size(); ++i) {
                    const glm::vec3 d = glm::vec3(x, 0.0f, z) - cloud.positions[i];
                    const glm::vec3 s = glm::exp(cloud.log_scales[i]);
                    const float a = glm::dot(d, local_axis(cloud.rotations[i], 0)) / s.x;
                    const float b = glm::dot(d, local_axis(cloud.rotations[i], 2)) / s.z;
                    const float opacity = 1.0f / (1.0f + std::exp(-cloud.opacity_logits[i]));
                    transmittance *= 1.0f - opacity * std::exp(-0.5f * (a * a + b * b));
                }
                worst = std::max(worst, transmittance);
            }
        }
        EXPECT_LT(worst, 0.05f);
    }
}

TEST(FineDetailBuilders, LowerDetailThinsEveryBuilder) {
    auto counts = [](float detail) {
        SplatCloud cloud;
        synth::Rng rng(2);
        std::vector<std::size_t> n;
        n.push_back(synth::append_ground(cloud, glm::vec3(0.0f), 1.0f, rng, detail).size());
        n.push_back(synth::append_grass(cloud, glm::vec3(0.0f), 0.5f, 1000.0f, rng, detail).size());
        n.push_back(synth::append_rock(cloud, glm::vec3(0.0f), glm::vec3(0.3f), rng, detail).size());
        synth::TreeStyle style;
        style.detail = detail;
        n.push_back(synth::append_tree(cloud, glm::vec3(0.0f), 3.0f, rng, style).leaves.size());
        const auto fence =
            synth::append_picket_fence(cloud, glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), 0.8f, rng, detail);
        n.push_back(fence.boards.size());
        return n;
    };
    const auto full = counts(1.0f), quarter = counts(0.25f);
    for (std::size_t k = 0; k < full.size(); ++k) {
        EXPECT_GT(quarter[k], 0u) << "builder " << k;
        EXPECT_LT(quarter[k], full[k]) << "builder " << k;
    }
    // Grass blades are exactly density × detail × area, two Gaussians each.
    EXPECT_EQ(full[1], 2u * 785u);
}

TEST(FineDetailBuilders, BadArgumentsThrowNamingTheBuilderAndArgument) {
    SplatCloud cloud;
    synth::Rng rng(1);
    const float nan = std::nanf("");
    EXPECT_NE(error_of([&] {
                  synth::append_ground(cloud, glm::vec3(0.0f), -1.0f, rng);
              }).find("append_ground(): radius must be a positive number, got -1"),
              std::string::npos);
    EXPECT_NE(error_of([&] {
                  synth::append_grass(cloud, glm::vec3(nan), 1.0f, 100.0f, rng);
              }).find("append_grass(): centre is not finite"),
              std::string::npos);
    EXPECT_NE(error_of([&] {
                  synth::make_fine_detail_scene({1, 0.0f});
              }).find("detail must be in [0.01, 16], got 0"),
              std::string::npos);
    EXPECT_NE(error_of([&] {
                  synth::append_picket_fence(cloud, glm::vec3(0.0f), glm::vec3(0.1f, 0.0f, 0.0f), 1.0f, rng);
              }).find("less than one board pitch"),
              std::string::npos);
    EXPECT_TRUE(cloud.empty());
}

TEST(FineDetailRng, IsReproducibleAndWellDistributed) {
    synth::Rng a(42), b(42), other_stream(42, 1);
    EXPECT_EQ(a.next_u64(), b.next_u64());
    EXPECT_NE(b.next_u64(), other_stream.next_u64());
    double sum = 0.0, sum_squares = 0.0, uniform_sum = 0.0;
    constexpr int kDraws = 100000;
    for (int i = 0; i < kDraws; ++i) {
        const float n = a.normal();
        sum += n;
        sum_squares += static_cast<double>(n) * n;
        const float u = a.uniform();
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        uniform_sum += u;
        const int k = a.uniform_int(-2, 3);
        ASSERT_GE(k, -2);
        ASSERT_LE(k, 3);
    }
    EXPECT_NEAR(sum / kDraws, 0.0, 0.02);
    EXPECT_NEAR(sum_squares / kDraws, 1.0, 0.02);
    EXPECT_NEAR(uniform_sum / kDraws, 0.5, 0.01);
}
