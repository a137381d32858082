// The real files (in tests/data or ../shared/data): Gaussian counts, SH degrees, load times, sanity
// of the decoded values, and a cross-format check of biker.compressed.ply against biker.spz.
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"
#include "test_support.h"

using splat_io_test::real_splat;
using splat_lod::LoadReport;
using splat_lod::SplatCloud;

namespace {

struct Loaded {
    SplatCloud cloud;
    LoadReport report;
};

Loaded timed_load(const std::string& relative) {
    Loaded out;
    const auto start = std::chrono::steady_clock::now();
    out.cloud = splat_lod::load_splat_file(real_splat(relative), &out.report);
    const auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[ load     ] " << relative << ": " << out.cloud.size() << " Gaussians, " << out.report.format << ", "
              << ms << " ms\n";
    return out;
}

void expect_sane(const Loaded& l, std::size_t count, int sh_degree) {
    EXPECT_EQ(l.report.gaussians_in_file, count);
    EXPECT_EQ(l.report.dropped(), 0u);
    EXPECT_EQ(l.cloud.size(), count);
    EXPECT_EQ(l.cloud.sh_degree, sh_degree);
    for (const auto& w : l.report.warnings) ADD_FAILURE() << "unexpected warning: " << w;
    for (const auto& r : l.cloud.rotations) ASSERT_NEAR(r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z, 1.0f, 1e-5f);
}

}  // namespace

TEST(SplatIoRealFiles, CompressedPlyBiker) {
    ENGINE_REQUIRE_DATA("splats/playcanvas-engine/biker.compressed.ply");
    const Loaded l = timed_load("playcanvas-engine/biker.compressed.ply");
    EXPECT_EQ(l.report.format, "PlayCanvas compressed PLY");
    expect_sane(l, 152746, 0);
}

TEST(SplatIoRealFiles, CompressedPlyGuitar) {
    ENGINE_REQUIRE_DATA("splats/playcanvas-engine/guitar.compressed.ply");
    expect_sane(timed_load("playcanvas-engine/guitar.compressed.ply"), 90854, 0);
}

TEST(SplatIoRealFiles, CompressedPlyFixtureWithShDegree3) {
    ENGINE_REQUIRE_DATA("splats/playcanvas-engine/test-fixture-64.compressed.ply");
    const Loaded l = timed_load("playcanvas-engine/test-fixture-64.compressed.ply");
    expect_sane(l, 64, 3);
    // Quantised SH lie in [-4, 4] and are not all zero.
    float largest = 0.0f;
    for (float v : l.cloud.sh_rest) {
        ASSERT_LE(std::fabs(v), 4.0f);
        largest = std::max(largest, std::fabs(v));
    }
    EXPECT_GT(largest, 0.01f);
}

TEST(SplatIoRealFiles, SpzV4Biker) {
    ENGINE_REQUIRE_SHARED_DATA();
    const Loaded l = timed_load("playcanvas-engine/biker.spz");
    EXPECT_EQ(l.report.format, "SPZ v4 (zstd)");
    expect_sane(l, 152746, 0);
}

TEST(SplatIoRealFiles, DonutPly) {
    ENGINE_REQUIRE_DATA("splats/gshairlod-donut/fused.ply");
    expect_sane(timed_load("gshairlod-donut/fused.ply"), 45624, 0);
}

TEST(SplatIoRealFiles, SogV1Logo) {
    ENGINE_REQUIRE_SHARED_DATA();
    const Loaded l = timed_load("playcanvas-engine/playcanvas-logo-sog");
    EXPECT_EQ(l.report.format, "PlayCanvas SOG v1");
    expect_sane(l, 307128, 0);
}

TEST(SplatIoRealFiles, SogV2PlaybotLevel0StaysInsideTheLodTreeBounds) {
    ENGINE_REQUIRE_SHARED_DATA();
    const Loaded l = timed_load("playcanvas-engine/playbot-lod-sog/0_0");
    EXPECT_EQ(l.report.format, "PlayCanvas SOG v2");
    expect_sane(l, 500000, 2);
    std::ifstream in(real_splat("playcanvas-engine/playbot-lod-sog/lod-meta.json"));
    const auto bound = nlohmann::json::parse(in)["tree"]["bound"];
    // 16-bit quantisation in log space: a step of at most (range / 65535)·e^|x| ≈ 1e-4 here.
    for (const auto& p : l.cloud.positions)
        for (int k = 0; k < 3; ++k) {
            ASSERT_GE(p[k], bound["min"][static_cast<std::size_t>(k)].get<float>() - 1e-3f);
            ASSERT_LE(p[k], bound["max"][static_cast<std::size_t>(k)].get<float>() + 1e-3f);
        }
}

TEST(SplatIoRealFiles, SogV2EveryPlaybotLevelLoads) {
    ENGINE_REQUIRE_SHARED_DATA();
    // lod-meta.json's tree gives each level's total count, split over two nodes.
    std::ifstream in(real_splat("playcanvas-engine/playbot-lod-sog/lod-meta.json"));
    const auto meta = nlohmann::json::parse(in);
    for (int level = 1; level < 7; ++level) {
        std::size_t expected = 0;
        for (const auto& node : meta["tree"]["children"])
            expected += node["lods"][std::to_string(level)]["count"].get<std::size_t>();
        // The tree's "file" index names the meta.json that holds the level.
        const auto file_index = meta["tree"]["children"][0]["lods"][std::to_string(level)]["file"].get<std::size_t>();
        const std::string holder = meta["filenames"][file_index].get<std::string>();
        const auto cloud = splat_lod::read_sog(real_splat("playcanvas-engine/playbot-lod-sog/" + holder));
        EXPECT_EQ(cloud.size(), expected) << holder;
        EXPECT_EQ(cloud.sh_degree, 2) << holder;
    }
}
