#pragma once
// An existing LOD chain to compare with at matched Gaussian counts: PlayCanvas's streamed SOG
// `lod-meta.json` (splat-transform's LOD output, splat_lod/core/streamed_sog.h), each level read as the
// whole scene at that level, whether one file holds it or its ranges are spread over many chunk files.
// Errors name the file and the problem.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/eval/eval_run.h"

namespace splat_lod::eval {

struct LodChainLevel {
    int level = 0;                             // 0 is the finest
    std::string source;                        // "…/lod-meta.json#L": what load_splat_file reads for it
    std::vector<std::filesystem::path> files;  // the chunk files holding the level
    std::uint64_t gaussians = 0;               // the tree's counts for the level, summed over its leaves
};

struct LodChain {
    std::filesystem::path meta;
    std::vector<LodChainLevel> levels;  // finest first, one per level 0..n-1
};

// Throws engine::Error naming `path` when it is missing, not JSON, lacks "filenames" or "tree",
// points a level to a file index "filenames" does not have, leaves a level out of some part of the
// tree, or names a chunk file that does not exist.
LodChain read_lod_chain(const std::filesystem::path& path);

// "chain_L3": the method name a chain level's measurements carry.
std::string chain_method_name(int level);

// One comparison scene per level, each loaded only when measured and placed like a splat file
// given with --scene (stored axes, identity transform). A level whose file is `main_file` shares
// `main_cloud` instead of loading it a second time.
std::vector<ComparisonScene> chain_comparisons(const LodChain& chain, const std::filesystem::path& main_file,
                                               std::shared_ptr<const SplatCloud> main_cloud);

}  // namespace splat_lod::eval
