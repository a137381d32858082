#pragma once
// A user's capture turned into a streamed world: the same folder layout, manifest, chunk groups,
// checksums and commit as a generated world (world_generator.h), so the streamer and the game read it
// unchanged. Steps:
//   1. Survey (one read of the capture, part by part; capture_source.h): a strided sample of the
//      Gaussians gives the frame. Up: --up, or found from the data (the dominant normal of flat, opaque
//      Gaussians; the thinnest axis of the positions when there are too few or no normal dominates; its
//      sign towards the longer tail of heights, where trees, buildings and sky stand; within 5° of a
//      coordinate axis it snaps to that axis, within 30° for the thinnest axis). The footprint: the 1st–99th percentile
//      box of the centres in the horizontal plane. The chunk size: the largest power-of-two fraction of the footprint
//      at which no chunk of the sample holds more than max_chunk_gaussians. Then, with `quadtree`: where the
//      capture is sparse, four sibling squares whose sample estimates sum to at most the densest cell's
//      become one chunk, bottom-up, up to squares of half the root group's side (ChunkEntry::span); so
//      the grid is as fine as the densest spot needs and the sparse ground has fewer, larger chunks, none
//      fuller than the densest (the streamer's budgets are sized by what one chunk holds near the camera).
//   2. Binning (a second read): every Gaussian is turned into the world frame (Y up, the footprint's
//      centre snapped to the chunk grid at the origin; SH rotated with it) and appended by its centre
//      to its chunk's bin file on disk; buffers are flushed when they hold a quarter of the memory cap,
//      so memory does not grow with the capture.
//   3. Each bin is baked (the world's chunk recipe, cameras at the distances the chunk is seen from,
//      scaled with the chunk size), ordered by stream level and written; then the chunk groups, then
//      the manifest (the commit). Chunks are baked in parallel within the memory cap.
// Hard cases of real captures, each counted in the summary:
//   - NaN/Inf values or a zero quaternion: dropped by the readers;
//   - never visible (opacity ≤ 1/255) or degenerate (largest extent below 1e−7 of the footprint):
//     dropped;
//   - huge Gaussians (extent above half a chunk and above 64 times the capture's median: sky, background)
//     and centres outside the world box
//     (the footprint square, heights within the 1st–99th percentile widened by the footprint's size):
//     the far layer, one splat glTF drawn as a prop wherever the world is, so no chunk's bounds grow
//     by them; above far_layer_max the largest (by extent × opacity) are kept, the rest dropped;
//   - a chunk that no bake camera sees (a few stray Gaussians far above or below the ground grid): written
//     as it is, every Gaussian level 1 and drawn from any distance;
//   - a capture with nothing left, or whose kept centres have no horizontal extent (all at one point,
//     one Gaussian), is an error naming the capture.
// An import whose capture files and options are those of the world already in the folder is not done
// again (ImportOptions::force). A failed import leaves the folder's previous world untouched (the generation folder and
// the commit of world_generator.h). The unit of a capture is unknown: the import works at a scale σ = chunk size / 64
// (the generated world's 64 m chunks), applied to the bake cameras' heights, the groups' cells and the stream levels'
// reaches, so a capture in any unit streams like the generated world scaled.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "splat_lod/bake/bake.h"
#include "splat_lod/worldgen/world_generator.h"
#include "splat_lod/worldgen/world_shards.h"

namespace splat_lod::world {

enum class CaptureViews {
    automatic,  // aerial when the capture is flat and coarse (capture_survey.cpp: height span below 6 % and
                // median Gaussian extent above 2.5e-4 of the footprint), else ground
    ground,     // the generated world's chunk cameras: eye height, low flight, overview
    aerial,     // from above and oblique only
};

struct ImportOptions {
    std::filesystem::path capture;  // any capture (capture_source.h): a file, a streamed SOG, tiles
    std::filesystem::path output;   // the world's folder
    std::optional<glm::vec3> up;    // none: found from the data
    // The capture's training cameras (cameras.json, COLMAP images.txt or a folder with either; see
    // splat_lod/core/training_cameras.h), in the capture's frame: a chunk that at least 4 of them see well
    // is baked from up to 16 of those instead of the rings. Empty: the rings only.
    std::filesystem::path cameras;
    CaptureViews views = CaptureViews::automatic;
    std::uint64_t memory_bytes = std::uint64_t{3} << 30;  // resident memory the import aims to stay within
    std::uint64_t max_chunk_gaussians = 262144;           // the chunk size is chosen so no chunk holds more
    std::uint64_t far_layer_max = 262144;
    int threads = 0;  // chunks baked at once (0: all cores), lowered to fit the memory cap
    bake::BakeOptions bake = default_world_bake_options();
    int bake_width = 512, bake_height = 384;
    bool groups = true;
    ChunkCodec chunk_codec = ChunkCodec::compact;  // as WorldOptions::chunk_codec
    // Merge sparse cells into chunks of several cells (step 1, "the quadtree"). Off by default: a merged
    // chunk streams its finer levels over its whole square once the camera is near any of it, which cost
    // the re-imported default world up to 1.0 dB on its ground and canopy frames (docs/results.md).
    bool quadtree = false;
    // Tuning of the out-of-core path (0: from memory_bytes): the largest part of a cut PLY read at once,
    // and how many bytes of binned Gaussians are buffered before they are appended to the bin files.
    std::uint64_t part_records = 0, bin_flush_bytes = 0;
    // Import again even when the folder holds this capture's world already (same files by path, size and
    // modification time, same options: the manifest's generator names their checksum).
    bool force = false;
    std::function<void(const WorldProgress&)> progress;
};

// What the survey found and what was done with every Gaussian.
struct ImportSummary {
    std::string run = "imported world";  // or "shard I/N", "merged world": how the summary names its chunks
    bool cached = false;                 // the folder's world was this import already: nothing was done
    std::string capture_description;     // "streamed SOG level 0: 8 chunk files"
    glm::dvec3 up{0.0, 1.0, 0.0};        // in the capture's frame
    std::string up_source;               // "given", "flat Gaussians", "thinnest axis"
    glm::dmat3 rotation{1.0};            // capture → world
    glm::dvec3 translation{0.0};
    bool aerial = false;
    double flatness = 0.0, coarseness = 0.0;             // height span and median extent over the footprint
    float chunk_size = 0.0f, size = 0.0f, scale = 1.0f;  // scale σ = chunk size / 64
    std::uint64_t read = 0;                              // Gaussians the readers returned
    std::uint64_t dropped_by_reader = 0;                 // NaN/Inf, zero quaternions
    std::uint64_t invisible = 0, degenerate = 0;         // dropped here
    std::uint64_t far_huge = 0, far_outside = 0;         // sent to the far layer
    std::uint64_t far_dropped = 0;                       // beyond far_layer_max
    std::uint64_t far_layer = 0;                         // in the far layer's file
    std::uint64_t binned = 0;                            // in chunks
    std::uint64_t bin_flushes = 0;                       // times the bins' buffers were written out
    std::size_t unbaked_chunks = 0;                      // chunks no bake camera sees, written as they are
    std::size_t merged_chunks = 0;                       // chunks of more than one grid cell (the quadtree)
    int largest_span = 0;                                // the largest chunk: 2^span cells a side
    std::size_t training_cameras = 0;                    // read from options.cameras
    std::size_t training_camera_chunks = 0;              // chunks baked from training cameras
    std::uint64_t peak_rss_bytes = 0;                    // the process's high-water mark at the end
    WorldSummary world;
};

struct ImportResult {
    WorldManifest manifest;  // a shard's: its record
    ImportSummary summary;
    std::filesystem::path record;  // a shard's record file (empty for a whole import or a merge)
};

// Imports options.capture into options.output (see the top of this file). Throws engine::Error
// naming the capture, chunk or file on any failure, after removing its own files.
ImportResult import_world(const ImportOptions& options);

// Sharded imports, for batch schedulers as sharded generated worlds (world_shards.h), the same bytes as
// import_world(). Shard I of N reads the whole capture (survey and binning), keeps the chunks whose
// grid index k (rows of increasing z, each of increasing x, over the whole grid) has k mod N = I − 1,
// bakes them into <output>/staging-import-<fingerprint>/gen/ and writes its record there
// (shard-<I>-of-<N>.json: a manifest of its chunks, checksums included; shard 1's also names the far
// layer). Shards hold the staging folder's lock shared and touch nothing else, so they may run at once
// while a game streams the folder's current world. A shard whose record is there and matches its files is
// not baked again (without options.force); nothing is done when the folder's world is this import.
ImportResult import_world_shard(const ImportOptions& options, const WorldShard& shard);

// The merge, under the folder's lock and the staging folder's exclusive one (refused while a shard
// writes): needs the records of all N shards of one N, checks each chunk file against its record,
// pools the chunk groups in the staging folder, renames the staged generation to the next gen-<n>,
// commits world.json and removes the staging folder. An error (a shard missing, a file not matching)
// names it and leaves the folder's world as it was.
ImportResult merge_import_shards(const ImportOptions& options);

// The summary's lines: frame, rejections, chunks, stage times.
std::string format_import_summary(const ImportSummary& summary);

}  // namespace splat_lod::world
