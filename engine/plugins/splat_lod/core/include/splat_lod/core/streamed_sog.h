#pragma once
// PlayCanvas's streamed SOG (splat-transform's LOD output), read as a whole scene per level:
//   {"lodLevels": 7, "filenames": ["0_0/meta.json", "0_1/meta.json", "1_0/meta.json", ...],
//    "tree": {"children": [{"lods": {"0": {"file": 0, "offset": 0, "count": 248155}, ...}}, ...]}}
// Every leaf of the octree (a node with "lods") names, per level, a range [offset, offset + count) of
// the Gaussians of one chunk file (an ordinary SOG meta.json). Level 0 is the finest. The whole scene
// at level L is the union over every leaf of its range for L: a level is usually spread over many
// chunk files, and one chunk file may hold the ranges of several leaves. Coarser levels are another
// tool's LOD (merged Gaussians), not training data.
//
// The whole scene at a level reads through capture_source.h (read_capture("lod-meta.json#L")).
// Reading is file by file: a caller that processes one StreamedSogFile at a time holds one chunk
// file's Gaussians, never the whole level (the world import relies on it).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::io {

// A leaf's range of one chunk file, and where the leaf is ("tree.children[1]") for messages.
struct StreamedSogRange {
    std::uint64_t offset = 0;
    std::uint64_t count = 0;
    std::string where;
};

// What one level takes from one chunk file: its ranges sorted by offset, never overlapping.
struct StreamedSogFile {
    std::filesystem::path file;  // the chunk's meta.json, resolved against the folder of lod-meta.json
    std::vector<StreamedSogRange> ranges;
    std::uint64_t gaussians = 0;  // the ranges' counts summed
};

struct StreamedSogLevel {
    int level = 0;
    std::vector<StreamedSogFile> files;  // in order of first use by the tree's leaves
    std::uint64_t gaussians = 0;         // the tree's counts for the level, summed over its leaves
    std::string missing_in;              // a leaf that lists no range for the level ("" when none)
};

struct StreamedSog {
    std::filesystem::path meta;
    std::vector<StreamedSogLevel> levels;  // one per level, 0 (finest) first
};

// True for a file named lod-meta.json, or a folder holding one.
bool is_streamed_sog(const std::filesystem::path& path);

// Parses and checks lod-meta.json (or the folder holding it). Throws engine::Error naming the file
// when it is missing, not JSON, lacks "filenames" or "tree", names a chunk file outside its folder
// (an absolute path or a ".." component), points a range to a file index that
// "filenames" does not have, has overlapping ranges in one file, levels beyond "lodLevels", or names a
// chunk file that does not exist (reported for the first level that uses it).
StreamedSog read_streamed_sog_meta(const std::filesystem::path& path);

// The level's description, or an error naming the file when the level does not exist or some leaf
// lists no range for it (the scene at that level would have a hole).
const StreamedSogLevel& streamed_sog_level(const StreamedSog& sog, int level);

// The Gaussians of one chunk file's ranges, in range order, sanitised like every reader's output
// (NaN, zero quaternions dropped and counted). A range past the end of the chunk file, or a chunk file
// that is missing or corrupt, throws engine::Error naming that file and the leaf.
SplatCloud read_streamed_sog_file(const StreamedSogFile& part, LoadReport* report = nullptr);

}  // namespace splat_lod::io
