// Hostile SOG input, built from a copy of playbot's smallest level (6_0, 1,873 Gaussians):
// malformed or lying meta.json variants, missing, truncated and lying WebP textures. Every
// failure must be an engine::Error naming the file at fault.
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"
#include "test_support.h"

using nlohmann::json;
using splat_io_test::error_of;

namespace {

namespace fs = std::filesystem;

class SplatIoHostileSog : public ::testing::Test {
protected:
    void SetUp() override {
        ENGINE_REQUIRE_SHARED_DATA();
        const fs::path source = splat_io_test::real_splat("playcanvas-engine/playbot-lod-sog/6_0");
        dir_ = engine::test::output_dir("splat_io") / "sog_hostile";
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        for (const auto& entry : fs::directory_iterator(source))
            fs::copy_file(entry.path(), dir_ / entry.path().filename(), fs::copy_options::overwrite_existing);
        std::ifstream in(dir_ / "meta.json");
        meta_ = json::parse(in);
    }

    // Writes `text` as <name> next to the textures and returns the reader's error.
    std::string error_for_text(const std::string& name, const std::string& text) {
        engine::write_text_file_atomic(dir_ / name, text);
        return error_of([&] { splat_lod::read_sog(dir_ / name); });
    }

    std::string error_for(const std::function<void(json&)>& edit) {
        json meta = meta_;
        edit(meta);
        return error_for_text("variant.json", meta.dump());
    }

    static void expect_has(const std::string& error, const std::string& fragment) {
        EXPECT_NE(error.find(fragment), std::string::npos) << "expected \"" << fragment << "\" in: " << error;
    }

    fs::path dir_;
    json meta_;
};

}  // namespace

TEST_F(SplatIoHostileSog, TheUnmodifiedCopyLoads) {
    splat_lod::LoadReport report;
    const auto cloud = splat_lod::read_sog(dir_, &report);
    EXPECT_EQ(cloud.size(), 1873u);
    EXPECT_EQ(cloud.sh_degree, 2);
    EXPECT_TRUE(report.warnings.empty());
}

TEST_F(SplatIoHostileSog, MalformedMetaJson) {
    expect_has(error_for_text("variant.json", "{\"version\": 2, \"count\": "), "variant.json: malformed JSON");
    expect_has(error_for_text("variant.json", "[1, 2]"), "variant.json: meta: expected a JSON object");
    expect_has(error_for([](json& m) { m.erase("scales"); }), "variant.json: meta.scales: missing");
    expect_has(error_for([](json& m) { m["means"]["mins"] = {1, 2}; }), "means.mins: expected an array of 3 numbers");
    expect_has(error_for([](json& m) { m["means"]["maxs"][1] = "high"; }), "means.maxs[1]: expected a number");
    expect_has(error_for([](json& m) { m["scales"]["codebook"].erase(0); }),
               "scales.codebook: expected an array of 256");
    expect_has(error_for([](json& m) { m["sh0"]["codebook"][5] = 1e39; }), "sh0.codebook[5]: not a finite float");
    expect_has(error_for([](json& m) { m["count"] = -1; }), "count: expected a non-negative integer");
    expect_has(error_for([](json& m) { m["count"] = "1873"; }), "count: expected a non-negative integer");
    expect_has(error_for([](json& m) { m["version"] = 3; }), "version: unsupported SOG version 3");
    expect_has(error_for([](json& m) { m["quats"]["files"] = json::array(); }), "quats.files: expected an array of 1");
    expect_has(error_for([](json& m) { m["shN"]["bands"] = 4; }), "shN.bands: 4 is not 1..3");
}

TEST_F(SplatIoHostileSog, FileNamesMustStayInsideTheFolder) {
    expect_has(error_for([](json& m) { m["quats"]["files"][0] = "../6_0/quats.webp"; }),
               "quats.files: \"../6_0/quats.webp\" is not a plain file name");
    expect_has(error_for([](json& m) { m["scales"]["files"][0] = "/etc/passwd"; }), "is not a plain file name");
    expect_has(error_for([](json& m) { m["scales"]["files"][0] = ".."; }), "is not a plain file name");
}

TEST_F(SplatIoHostileSog, CountsTheTexturesCannotHold) {
    expect_has(error_for([](json& m) { m["count"] = 187300; }), "but 187300 are needed");
    expect_has(error_for([](json& m) { m["count"] = 1000000000000ull; }), "means_l.webp: ");
    // The palette says more entries than the centroid texture holds, or the wrong band count.
    expect_has(error_for([](json& m) { m["shN"]["count"] = 1u << 20; }), "palette entries, meta.json says 1048576");
    expect_has(error_for([](json& m) { m["shN"]["bands"] = 3; }), "width 512, expected 960 for 3 SH bands");
}

TEST_F(SplatIoHostileSog, MissingTruncatedAndLyingTextures) {
    expect_has(error_for([](json& m) { m["quats"]["files"][0] = "missing.webp"; }), "missing.webp: cannot open");
    fs::remove(dir_ / "scales.webp");
    expect_has(error_of([&] { splat_lod::read_sog(dir_); }), "scales.webp: cannot open");

    const auto quats = engine::read_binary_file(dir_ / "quats.webp");
    engine::write_file_atomic(dir_ / "quats_cut.webp", std::span(quats).first(quats.size() / 2));
    expect_has(error_for([](json& m) { m["quats"]["files"][0] = "quats_cut.webp"; }),
               "quats_cut.webp: WebP decoding failed");
    engine::write_file_atomic(dir_ / "quats_tiny.webp", std::span(quats).first(20));
    expect_has(error_for([](json& m) { m["quats"]["files"][0] = "quats_tiny.webp"; }),
               "quats_tiny.webp: not a WebP image");

    // VP8L header (after "RIFF....WEBPVP8L", size, 0x2f): 14 bits width-1, 14 bits height-1.
    ASSERT_EQ(std::string(quats.begin() + 12, quats.begin() + 16), "VP8L");
    auto huge = quats;
    huge[21] = 0xff;
    huge[22] = 0xff;
    huge[23] = 0xff;
    huge[24] = static_cast<std::uint8_t>((huge[24] & 0xf0) | 0x0f);
    engine::write_file_atomic(dir_ / "quats_huge.webp", huge);
    expect_has(error_for([](json& m) { m["quats"]["files"][0] = "quats_huge.webp"; }),
               "quats_huge.webp: claims 16384x16384 texels, implausible");
}

TEST_F(SplatIoHostileSog, FoldersWithoutMetaJson) {
    fs::remove(dir_ / "meta.json");
    expect_has(error_of([&] { splat_lod::read_sog(dir_); }), "sog_hostile: folder has no meta.json");
    expect_has(error_of([&] { splat_lod::read_sog(dir_ / "absent.json"); }), "absent.json: cannot open");
}

TEST_F(SplatIoHostileSog, AV1MetaOverTheSameTexturesDecodesTheV1Path) {
    // v1 has no version, takes the count from means.shape, ranges instead of codebooks and infers
    // the SH bands from the centroid texture width (512 = 64 entries x 8 coefficients: 2 bands).
    json v1 = {{"means",
                {{"shape", {1873, 3}},
                 {"mins", meta_["means"]["mins"]},
                 {"maxs", meta_["means"]["maxs"]},
                 {"files", meta_["means"]["files"]}}},
               {"scales", {{"mins", {-10, -10, -10}}, {"maxs", {0, 0, 0}}, {"files", {"scales.webp"}}}},
               {"quats", {{"files", {"quats.webp"}}}},
               {"sh0", {{"mins", {-2, -2, -2, -6}}, {"maxs", {2, 2, 2, 6}}, {"files", {"sh0.webp"}}}},
               {"shN", {{"mins", -1}, {"maxs", 1}, {"files", {"shN_centroids.webp", "shN_labels.webp"}}}}};
    engine::write_text_file_atomic(dir_ / "v1.json", v1.dump());
    splat_lod::LoadReport report;
    const auto v1_cloud = splat_lod::read_sog(dir_ / "v1.json", &report);
    const auto v2_cloud = splat_lod::read_sog(dir_);
    EXPECT_EQ(report.format, "PlayCanvas SOG v1");
    ASSERT_EQ(v1_cloud.size(), 1873u);
    EXPECT_EQ(v1_cloud.sh_degree, 2);
    EXPECT_EQ(v1_cloud.positions, v2_cloud.positions) << "means decode the same in both versions";
    for (std::size_t i = 0; i < v1_cloud.size(); ++i) {
        ASSERT_GE(v1_cloud.log_scales[i].x, -10.0f);
        ASSERT_LE(v1_cloud.log_scales[i].x, 0.0f);
        ASSERT_GE(v1_cloud.opacity_logits[i], -6.0f);
        ASSERT_LE(v1_cloud.opacity_logits[i], 6.0f);
    }
}

TEST_F(SplatIoHostileSog, RandomMetaJsonEditsLoadOrThrowEngineErrors) {
    const std::string original = meta_.dump();
    std::mt19937 rng(17);
    const std::string alphabet = "0123456789-.e,:[]{}\"x ";
    for (int trial = 0; trial < 60; ++trial) {
        std::string text = original;
        for (int e = 0; e < 3; ++e) text[rng() % text.size()] = alphabet[rng() % alphabet.size()];
        engine::write_text_file_atomic(dir_ / "mutant.json", text);
        splat_lod::LoadReport quiet;
        const std::string error = error_of([&] { splat_lod::read_sog(dir_ / "mutant.json", &quiet); });
        EXPECT_TRUE(error.empty() || error.find("mutant.json") != std::string::npos) << error;
    }
}
