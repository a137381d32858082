#pragma once
// An existing LOD chain to compare with at matched Gaussian counts: PlayCanvas's `lod-meta.json`
// (splat-transform's LOD output), read as one whole-scene file per level:
//   {"lodLevels": 7, "filenames": ["0_0/meta.json", "2_0/meta.json", ...],
//    "tree": {"children": [{"lods": {"0": {"file": 0, "offset": 0, "count": 248155}, ...}}, ...]}}
// Every leaf of the tree (a node with "lods") names, per level, the index into "filenames" of the
// file holding that part of the level. A level is usable here only when all leaves point to the
// same file, which then holds the whole scene at that level. Errors name the file and the problem.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/eval/eval_run.h"

namespace splat_lod::eval {

struct LodChainLevel {
    int level = 0;                // 0 is the finest
    std::filesystem::path file;   // resolved against the folder of lod-meta.json
    std::uint64_t gaussians = 0;  // the tree's counts for the level, summed over its leaves
};

struct LodChain {
    std::filesystem::path meta;
    std::vector<LodChainLevel> levels;  // finest first, one per level 0..n-1
};

// Throws engine::Error naming `path` when it is missing, not JSON, lacks "filenames" or "tree",
// points a level to a file index "filenames" does not have, splits a level over several files,
// leaves a level out of some part of the tree, or names a level file that does not exist.
LodChain read_lod_chain(const std::filesystem::path& path);

// "chain_L3": the method name a chain level's measurements carry.
std::string chain_method_name(int level);

// One comparison scene per level, each loaded only when measured and placed like a splat file
// given with --scene (stored axes, identity transform). A level whose file is `main_file` shares
// `main_cloud` instead of loading it a second time.
std::vector<ComparisonScene> chain_comparisons(const LodChain& chain, const std::filesystem::path& main_file,
                                               std::shared_ptr<const SplatCloud> main_cloud);

}  // namespace splat_lod::eval
