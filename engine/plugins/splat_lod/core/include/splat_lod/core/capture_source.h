#pragma once
// A capture as users bring it, read as one scene, one part at a time. A capture is named by one path:
//   - a splat file of any format splat_io.h reads (a large binary INRIA PLY is cut into record ranges);
//   - a streamed SOG: lod-meta.json or the folder holding it, at its finest level (0), or at level L
//     with the suffix "#L" ("capture/lod-meta.json#2"); each chunk file is one part;
//   - a streamed world's world.json (world_manifest.h): every chunk's finest (bake level 1) Gaussians,
//     one part per chunk, without LOD attributes: the world exported as the capture it stands for;
//   - tiles of one capture (block-wise trainings): a folder whose splat files (.ply, .spz, .splat,
//     .glb, .gltf) and SOG folders (holding meta.json or lod-meta.json) are read in name order, or a
//     text list (.txt) naming one splat file, folder or streamed SOG per line (relative to the list's
//     folder; blank lines and lines starting with '#' are skipped). Tiles are concatenated: overlapping
//     borders stay as the trainings made them.
// Reading part by part bounds memory by the largest part (the world import relies on it);
// read_capture() concatenates them (what load_splat_file does for these inputs). No reader converts
// axes: the data come back in the files' own convention.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/core/streamed_sog.h"
#include "splat_lod/core/world_manifest.h"

namespace splat_lod {

struct CapturePart {
    enum class Kind {
        whole_file,   // any splat file read by load_splat_file
        ply_records,  // records [begin, end) of a binary little-endian INRIA PLY
        sog_ranges,   // one chunk file of a streamed SOG level
        world_chunk,  // the bake-level-1 Gaussians of a world chunk (`chunk` is its manifest entry)
    };
    Kind kind = Kind::whole_file;
    std::filesystem::path file;
    std::uint64_t begin = 0, end = 0;                // ply_records
    io::StreamedSogFile sog;                         // sog_ranges
    std::shared_ptr<const world::ChunkEntry> chunk;  // world_chunk
    std::uint64_t gaussians = 0;  // expected (header or tree counts); 0 when not known before reading
    std::string label() const;    // "tile.ply records 0..1048576", for progress and messages
};

struct Capture {
    std::filesystem::path path;  // as given, "#L" included
    std::string description;     // "streamed SOG level 0: 53 chunk files", "3 tiles", "INRIA PLY"
    std::vector<CapturePart> parts;
    std::uint64_t gaussians() const;  // the parts' expected counts summed
};

// Default largest part of a cut PLY: 1M records (about 250 MB at SH degree 3).
inline constexpr std::uint64_t kCapturePartRecords = std::uint64_t{1} << 20;

// Splits "file#L" into the file and the level; no suffix gives level −1. A suffix that is not a
// decimal level throws engine::Error naming the path.
std::filesystem::path capture_file_and_level(const std::filesystem::path& path, int* level);

// True when `path` names a streamed SOG or a set of tiles (what load_splat_file reads through here).
bool is_multi_part_capture(const std::filesystem::path& path);

// Lists the capture's parts without reading Gaussians (headers and lod-meta.json only). Errors name
// the path and the problem: nothing there, a folder with no splat file, an empty list, "#L" on a file
// that is not a streamed SOG, a level the streamed SOG does not have.
Capture open_capture(const std::filesystem::path& path, std::uint64_t max_part_records = kCapturePartRecords);

// One part's Gaussians, sanitised as every reader's are (the report counts what was dropped).
SplatCloud read_capture_part(const CapturePart& part, LoadReport* report = nullptr);

// Every part, concatenated (append_cloud: highest SH degree, common extras).
SplatCloud read_capture(const std::filesystem::path& path, LoadReport* report = nullptr);

// Adds a part's counts and warnings to a running total (the first format named wins).
void merge_load_report(LoadReport& total, const LoadReport& part);

}  // namespace splat_lod
