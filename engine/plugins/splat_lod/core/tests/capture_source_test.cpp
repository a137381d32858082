// Captures in several files read as one scene (capture_source.h): a streamed SOG whose level is
// spread over chunk files, tile folders and lists, a large PLY read in record ranges; each gives the
// same Gaussians as its single-file equivalent, and every broken input is named with its problem.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/capture_source.h"
#include "splat_lod/core/splat_io.h"
#include "test_support.h"

using splat_io_test::error_of;
using splat_io_test::make_cloud;
using splat_lod::SplatCloud;
namespace fs = std::filesystem;

namespace {

// Every stored value equal, Gaussian by Gaussian (the readers are exact for these formats).
void expect_same_gaussians(const SplatCloud& a, const SplatCloud& b) {
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.sh_degree, b.sh_degree);
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a.positions[i], b.positions[i]) << i;
        ASSERT_EQ(a.log_scales[i], b.log_scales[i]) << i;
        ASSERT_EQ(a.opacity_logits[i], b.opacity_logits[i]) << i;
        ASSERT_EQ(a.sh_dc[i], b.sh_dc[i]) << i;
        ASSERT_EQ(a.rotations[i].w, b.rotations[i].w) << i;
        ASSERT_EQ(a.rotations[i].z, b.rotations[i].z) << i;
    }
    EXPECT_EQ(a.sh_rest, b.sh_rest);
}

// Gaussians [begin, end) of a cloud.
SplatCloud slice(const SplatCloud& cloud, std::uint32_t begin, std::uint32_t end) {
    std::vector<std::uint32_t> order;
    for (std::uint32_t i = begin; i < end; ++i) order.push_back(i);
    return cloud.permuted(order);
}

SplatCloud joined(std::vector<SplatCloud> parts) {
    SplatCloud whole;
    for (SplatCloud& part : parts) splat_lod::append_cloud(whole, std::move(part));
    return whole;
}

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = engine::test::output_dir("capture_source") / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void copy_sog_folder(const fs::path& from, const fs::path& to) {
    fs::create_directories(to);
    for (const auto& entry : fs::directory_iterator(from)) fs::copy_file(entry.path(), to / entry.path().filename());
}

// The real playbot level 3 (31,000 Gaussians) copied into two chunk folders, with a lod-meta.json whose
// three leaves spread level 0 over both: a [0, 12000) and [20000, 31000), b [12000, 20000).
fs::path spread_streamed_sog(const std::string& name) {
    const fs::path dir = fresh_dir(name);
    const fs::path level3 = splat_io_test::real_splat("playcanvas-engine/playbot-lod-sog/3_0");
    copy_sog_folder(level3, dir / "a");
    copy_sog_folder(level3, dir / "b");
    std::ofstream(dir / "lod-meta.json") << R"({"lodLevels": 1, "filenames": ["a/meta.json", "b/meta.json"],
      "tree": {"children": [
        {"lods": {"0": {"file": 0, "offset": 0, "count": 12000}}},
        {"children": [{"lods": {"0": {"file": 1, "offset": 12000, "count": 8000}}}]},
        {"lods": {"0": {"file": 0, "offset": 20000, "count": 11000}}}]}})";
    return dir;
}

TEST(CaptureSource, StreamedSogLevelSpreadOverChunkFilesReadsLikeTheWholeFile) {
    ENGINE_REQUIRE_SHARED_DATA();
    const fs::path dir = spread_streamed_sog("spread");
    const SplatCloud single = splat_lod::read_sog(dir / "a");
    ASSERT_EQ(single.size(), 31000u);
    splat_lod::LoadReport report;
    const SplatCloud streamed = splat_lod::load_splat_file(dir / "lod-meta.json", &report);
    // File a's ranges first (in offset order), then file b's.
    expect_same_gaussians(streamed,
                          joined({slice(single, 0, 12000), slice(single, 20000, 31000), slice(single, 12000, 20000)}));
    EXPECT_NE(report.format.find("streamed SOG level 0: 2 chunk files"), std::string::npos) << report.format;
    EXPECT_EQ(splat_lod::detect_splat_format(dir), splat_lod::SplatFileFormat::streamed_sog);
    EXPECT_EQ(splat_lod::load_splat_file(dir).size(), 31000u) << "the folder reads as its lod-meta.json";
    const splat_lod::Capture capture = splat_lod::open_capture(dir / "lod-meta.json");
    ASSERT_EQ(capture.parts.size(), 2u);
    EXPECT_EQ(capture.gaussians(), 31000u);
    EXPECT_EQ(splat_lod::read_capture_part(capture.parts[1]).size(), 8000u);
}

TEST(CaptureSource, RealStreamedSogReadsAnyLevelWhole) {
    ENGINE_REQUIRE_SHARED_DATA();
    const fs::path playbot = splat_io_test::real_splat("playcanvas-engine/playbot-lod-sog");
    EXPECT_EQ(splat_lod::load_splat_file(playbot / "lod-meta.json").size(), 500000u) << "the finest level";
    const SplatCloud level3 = splat_lod::load_splat_file(playbot.string() + "/lod-meta.json#3");
    expect_same_gaussians(level3, splat_lod::read_sog(playbot / "3_0"));
    const std::string beyond = error_of([&] { splat_lod::load_splat_file(playbot.string() + "/lod-meta.json#9"); });
    EXPECT_NE(beyond.find("has no level 9"), std::string::npos) << beyond;
}

TEST(CaptureSource, TileFolderAndListReadAsOneCapture) {
    const SplatCloud whole = make_cloud(300, 1, 7);
    const fs::path dir = fresh_dir("tiles");
    fs::create_directories(dir / "tiles");
    splat_lod::write_inria_ply(dir / "tiles" / "a_west.ply", slice(whole, 0, 120));
    splat_lod::write_gltf_splats(dir / "tiles" / "b_middle.glb", slice(whole, 120, 200));
    splat_lod::write_inria_ply(dir / "tiles" / "c_east.ply", slice(whole, 200, 300));
    std::ofstream(dir / "tiles" / "notes.md") << "not a tile";
    splat_lod::write_inria_ply(dir / "whole.ply", whole);
    const SplatCloud single = splat_lod::load_splat_file(dir / "whole.ply");

    // glTF stores linear scales: its tile is compared with itself read alone, the PLY tiles with the whole file.
    const SplatCloud middle = splat_lod::load_splat_file(dir / "tiles" / "b_middle.glb");
    EXPECT_EQ(splat_lod::detect_splat_format(dir / "tiles"), splat_lod::SplatFileFormat::tiles);
    expect_same_gaussians(splat_lod::load_splat_file(dir / "tiles"),
                          joined({slice(single, 0, 120), middle, slice(single, 200, 300)}));

    std::ofstream(dir / "capture.txt") << "# tiles of one training, east first\n\n"
                                       << "tiles/c_east.ply\n  tiles/a_west.ply  \ntiles/b_middle.glb\n";
    expect_same_gaussians(splat_lod::load_splat_file(dir / "capture.txt"),
                          joined({slice(single, 200, 300), slice(single, 0, 120), middle}));
}

TEST(CaptureSource, TilesOfDifferentShDegreesJoinAtTheHighest) {
    const fs::path dir = fresh_dir("degrees");
    splat_lod::write_inria_ply(dir / "a.ply", make_cloud(10, 0, 1));
    splat_lod::write_inria_ply(dir / "b.ply", make_cloud(5, 2, 2));
    const SplatCloud cloud = splat_lod::load_splat_file(dir);
    ASSERT_EQ(cloud.size(), 15u);
    EXPECT_EQ(cloud.sh_degree, 2);
    EXPECT_EQ(cloud.sh_rest_at(3, 4, 1), 0.0f) << "a degree-0 tile gets zero higher coefficients";
    EXPECT_EQ(cloud.sh_rest_at(12, 4, 1), make_cloud(5, 2, 2).sh_rest_at(2, 4, 1));
}

TEST(CaptureSource, LargePlyIsReadInRecordRanges) {
    const fs::path dir = fresh_dir("ranges");
    splat_lod::write_inria_ply(dir / "big.ply", make_cloud(100, 3, 3));
    const SplatCloud single = splat_lod::load_splat_file(dir / "big.ply");
    const splat_lod::Capture capture = splat_lod::open_capture(dir / "big.ply", 30);
    ASSERT_EQ(capture.parts.size(), 4u);
    EXPECT_EQ(capture.parts[3].begin, 90u);
    EXPECT_EQ(capture.parts[3].end, 100u);
    std::vector<SplatCloud> parts;
    for (const auto& part : capture.parts) parts.push_back(splat_lod::read_capture_part(part));
    expect_same_gaussians(joined(std::move(parts)), single);

    // Cut short after the listing: the part past the end says the file is truncated.
    fs::resize_file(dir / "big.ply", fs::file_size(dir / "big.ply") - 500);
    const std::string truncated = error_of([&] { splat_lod::read_capture_part(capture.parts[3]); });
    EXPECT_NE(truncated.find("big.ply"), std::string::npos) << truncated;
    EXPECT_NE(truncated.find("truncated"), std::string::npos) << truncated;
}

TEST(CaptureSource, BrokenCapturesAreNamedWithTheirProblem) {
    const fs::path dir = fresh_dir("broken");
    fs::create_directories(dir / "empty");
    std::ofstream(dir / "empty" / "readme.txt") << "nothing";
    const auto expect_error = [](const std::function<void()>& f, const std::vector<std::string>& parts) {
        const std::string message = error_of(f);
        for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
    };
    expect_error([&] { splat_lod::load_splat_file(dir / "empty"); }, {"empty", "holds no splat tile"});
    std::ofstream(dir / "none.txt") << "# only a comment\n";
    expect_error([&] { splat_lod::load_splat_file(dir / "none.txt"); }, {"none.txt", "names no file"});
    std::ofstream(dir / "absent.txt") << "missing_tile.ply\n";
    expect_error([&] { splat_lod::load_splat_file(dir / "absent.txt"); },
                 {"absent.txt", "line 1", "missing_tile.ply", "no such file"});
    splat_lod::write_inria_ply(dir / "one.ply", make_cloud(4, 0, 1));
    expect_error([&] { splat_lod::load_splat_file(dir.string() + "/one.ply#1"); }, {"one.ply", "#level"});
    expect_error([&] { splat_lod::load_splat_file(dir.string() + "/lod-meta.json#x"); }, {"#x", "not a level"});
    int level = -1;
    EXPECT_EQ(splat_lod::capture_file_and_level("lod-meta.json#2", &level), std::filesystem::path("lod-meta.json"));
    EXPECT_EQ(level, 2) << "a bare file name with a level";
    EXPECT_EQ(splat_lod::capture_file_and_level("a#b/lod-meta.json", &level),
              std::filesystem::path("a#b/lod-meta.json"));
    EXPECT_EQ(level, -1) << "a '#' in a folder name is not a level";
    // A header that claims far more records than the file holds is not cut into parts without end.
    {
        std::string bytes = engine::read_text_file(dir / "one.ply");
        bytes.replace(bytes.find("element vertex 4"), 16, "element vertex 1125899906842624");
        std::ofstream(dir / "lying.ply", std::ios::binary) << bytes;
    }
    EXPECT_EQ(splat_lod::open_capture(dir / "lying.ply", 1000).parts.size(), 1u);
    expect_error([&] { splat_lod::read_capture(dir / "lying.ply"); }, {"lying.ply"});
    std::ofstream(dir / "self.txt") << "self.txt\n";
    expect_error([&] { splat_lod::load_splat_file(dir / "self.txt"); }, {"self.txt", "nest deeper"});
}

TEST(CaptureSource, MissingOrTruncatedSogChunksAreNamed) {
    ENGINE_REQUIRE_SHARED_DATA();
    const fs::path dir = spread_streamed_sog("broken_sog");
    // A leaf asking for more records than its chunk holds (a chunk replaced by a smaller one).
    std::string text = engine::read_text_file(dir / "lod-meta.json");
    text.replace(text.find("\"count\": 11000"), 14, "\"count\": 11001");
    std::ofstream(dir / "lod-meta.json") << text;
    std::string message = error_of([&] { splat_lod::load_splat_file(dir / "lod-meta.json"); });
    EXPECT_NE(message.find("a/meta.json"), std::string::npos) << message;
    EXPECT_NE(message.find("tree.children[2]"), std::string::npos) << message;
    EXPECT_NE(message.find("31000"), std::string::npos) << message;

    fs::remove_all(dir / "b");
    message = error_of([&] { splat_lod::load_splat_file(dir / "lod-meta.json"); });
    EXPECT_NE(message.find("b/meta.json"), std::string::npos) << message;
    EXPECT_NE(message.find("does not exist"), std::string::npos) << message;

    // A chunk whose texture is cut short: the SOG reader's own error names the texture.
    text.replace(text.find("\"count\": 11001"), 14, "\"count\": 11000");
    std::ofstream(dir / "lod-meta.json") << text;
    copy_sog_folder(dir / "a", dir / "b");
    const fs::path means = dir / "b" / "means_l.webp";
    fs::resize_file(means, fs::file_size(means) / 2);
    message = error_of([&] { splat_lod::load_splat_file(dir / "lod-meta.json"); });
    EXPECT_NE(message.find("means_l.webp"), std::string::npos) << message;
}

}  // namespace
