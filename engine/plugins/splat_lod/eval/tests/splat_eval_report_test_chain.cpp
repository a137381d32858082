// The evaluation reading an LOD chain's lod-meta.json: the level files found through the tree, and
// every bad file named with its problem.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "splat_eval_report_test_helpers.h"
#include "splat_lod/eval/lod_chain.h"
#include "test_support.h"

namespace eval = splat_lod::eval;
using splat_eval_report_test::expect_error;

namespace {

// A chain folder with empty level files (reading the chain does not load them).
std::filesystem::path chain_folder(const std::string& name) {
    const auto folder = engine::test::output_dir("splat_eval_report") / name;
    std::filesystem::create_directories(folder);
    for (const char* level : {"0_0", "1_0", "2_0"}) {
        std::filesystem::create_directories(folder / level);
        std::ofstream(folder / level / "meta.json") << "{}";
    }
    return folder;
}

std::filesystem::path write_meta(const std::filesystem::path& folder, const std::string& text) {
    std::ofstream(folder / "lod-meta.json") << text;
    return folder / "lod-meta.json";
}

// PlayCanvas's layout: the file list is not in level order, two leaves share each level's file.
const char* kChain = R"({"lodLevels": 3, "filenames": ["0_0/meta.json", "2_0/meta.json", "1_0/meta.json"],
  "tree": {"children": [
    {"lods": {"0": {"file": 0, "offset": 0, "count": 600}, "1": {"file": 2, "offset": 0, "count": 300},
              "2": {"file": 1, "offset": 0, "count": 60}}},
    {"children": [{"lods": {"0": {"file": 0, "offset": 600, "count": 400}, "1": {"file": 2, "offset": 300, "count": 200},
                            "2": {"file": 1, "offset": 60, "count": 40}}}]}]}})";

TEST(SplatEvalChain, ReadsLevelFilesThroughTheTree) {
    const auto folder = chain_folder("good");
    const eval::LodChain chain = eval::read_lod_chain(write_meta(folder, kChain));
    ASSERT_EQ(chain.levels.size(), 3u);
    using Files = std::vector<std::filesystem::path>;
    EXPECT_EQ(chain.levels[0].files, Files{folder / "0_0/meta.json"});
    EXPECT_EQ(chain.levels[1].files, Files{folder / "1_0/meta.json"});
    EXPECT_EQ(chain.levels[2].files, Files{folder / "2_0/meta.json"});
    EXPECT_EQ(chain.levels[2].source, (folder / "lod-meta.json").string() + "#2");
    EXPECT_EQ(chain.levels[0].gaussians, 1000u);
    EXPECT_EQ(chain.levels[1].gaussians, 500u);
    EXPECT_EQ(chain.levels[2].gaussians, 100u);
    EXPECT_EQ(chain.levels[2].level, 2);
    EXPECT_EQ(eval::chain_method_name(2), "chain_L2");
    const auto comparisons = eval::chain_comparisons(chain, folder / "0_0/meta.json", nullptr);
    ASSERT_EQ(comparisons.size(), 3u);
    EXPECT_EQ(comparisons[1].method, "chain_L1");
    EXPECT_NE(comparisons[1].description.find("1_0/meta.json, 500 Gaussians"), std::string::npos)
        << comparisons[1].description;
}

// splat-transform's streamed output: a level spread over several chunk files, one of them shared
// with another level's ranges.
TEST(SplatEvalChain, ReadsLevelsSpreadOverSeveralChunkFiles) {
    const auto folder = chain_folder("spread");
    std::string spread = kChain;
    spread.replace(spread.find("\"file\": 2, \"offset\": 300"), 9, "\"file\": 1");
    const eval::LodChain chain = eval::read_lod_chain(write_meta(folder, spread));
    using Files = std::vector<std::filesystem::path>;
    EXPECT_EQ(chain.levels[1].files, (Files{folder / "1_0/meta.json", folder / "2_0/meta.json"}));
    EXPECT_EQ(chain.levels[1].gaussians, 500u);
    const auto comparisons = eval::chain_comparisons(chain, folder / "0_0/meta.json", nullptr);
    EXPECT_NE(comparisons[1].description.find("2 chunk files, 500 Gaussians"), std::string::npos)
        << comparisons[1].description;
}

TEST(SplatEvalChain, BadFilesNameFileAndProblem) {
    const auto folder = chain_folder("bad");
    expect_error([&] { eval::read_lod_chain(folder / "absent.json"); }, {"absent.json"});
    expect_error([&] { eval::read_lod_chain(write_meta(folder, "{\"filenames\": [")); },
                 {"lod-meta.json", "not valid JSON"});
    expect_error([&] { eval::read_lod_chain(write_meta(folder, "[]")); }, {"lod-meta.json", "object"});

    std::string no_filenames = kChain;
    no_filenames.replace(no_filenames.find("\"filenames\""), 11, "\"files\"");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, no_filenames)); },
                 {"lod-meta.json", "missing \"filenames\""});

    std::string bad_index = kChain;
    bad_index.replace(bad_index.find("\"file\": 1, \"offset\": 60"), 9, "\"file\": 7");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, bad_index)); },
                 {"lod-meta.json", "tree.children[1].children[0].lods[\"2\"]", "file index 7", "3 entries"});

    std::string overlap = kChain;
    overlap.replace(overlap.find("\"offset\": 300"), 13, "\"offset\": 299");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, overlap)); },
                 {"lod-meta.json", "level 1", "tree.children[1].children[0] overlaps tree.children[0]", "meta.json"});

    std::string beyond = kChain;
    beyond.replace(beyond.find("\"2\": {\"file\": 1, \"offset\": 60"), 6, "\"5\": {");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, beyond)); },
                 {"lod-meta.json", "level 5", "\"lodLevels\""});
    const char* missing_level = R"({"filenames": ["0_0/meta.json"], "tree": {"children": [
        {"lods": {"0": {"file": 0, "offset": 0, "count": 1}, "1": {"file": 0, "offset": 1, "count": 1}}},
        {"lods": {"0": {"file": 0, "offset": 2, "count": 1}}}]}})";
    expect_error([&] { eval::read_lod_chain(write_meta(folder, missing_level)); },
                 {"lod-meta.json", "level 1 is missing from tree.children[1]"});

    std::string outside = kChain;
    outside.replace(outside.find("\"2_0/meta.json\""), 15, "\"../2_0/meta.json\"");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, outside)); },
                 {"lod-meta.json", "\"filenames\"[1]", "leaves the folder"});

    std::string no_tree = kChain;
    no_tree.replace(no_tree.find("\"tree\""), 6, "\"bush\"");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, no_tree)); }, {"lod-meta.json", "missing \"tree\""});

    std::filesystem::remove(folder / "2_0/meta.json");
    expect_error([&] { eval::read_lod_chain(write_meta(folder, kChain)); },
                 {"lod-meta.json", "level 2", "2_0/meta.json", "does not exist"});
}

}  // namespace
