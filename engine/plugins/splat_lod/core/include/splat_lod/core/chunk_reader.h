#pragma once
// Reading part of a world chunk: the records [begin, end) of its LOD file (a binary little-endian
// INRIA PLY or a compressed chunk file, coarse level first, world_manifest.h), without reading the rest. A streamer
// loads a far chunk's coarse prefix (levels 4..l) first and the finer levels later as ranges that follow it.
#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {

// The Gaussians [begin, end) of the chunk file `file` (the manifest's folder / entry.file), decoded
// as the INRIA PLY reader decodes them (LOD attributes included; quaternions normalised), or for a
// compressed file as the records were quantised (compact_chunk.h). Reads the header and then the
// checksum blocks (world_manifest.h) that hold the range, seeking to the first one. Throws
// engine::Error naming the file when it is missing, its size differs from entry.file_bytes, its header
// does not match the entry (byte counts, vertex or block count, checksum), it ends early, a block read
// does not match its checksum or does not decode, a record is not finite, or the range is not within
// [0, prefix_count[0]].
SplatCloud read_chunk_range(const std::filesystem::path& file, const ChunkEntry& entry, std::uint64_t begin,
                            std::uint64_t end);

// The Gaussians of `level` alone (1..4): [prefix_count[level], prefix_count[level − 1]), with
// prefix_count[4] taken as 0. Loading levels 4, 3, 2, 1 in turn appends up to the whole file.
std::pair<std::uint64_t, std::uint64_t> level_range(const ChunkEntry& entry, int level);

// Where one record block lies in a chunk file.
struct BlockBytes {
    std::uint64_t offset = 0, size = 0;
};
// Every record block of the chunk file, in file order (record_crc32's): computed from the entry for a
// PLY file, read from a compressed file's header (checked against the entry as above).
std::vector<BlockBytes> record_block_bytes(const std::filesystem::path& file, const ChunkEntry& entry);

// The chunk drawn down to `level`: its first prefix_count[level − 1] Gaussians.
SplatCloud read_chunk_prefix(const std::filesystem::path& file, const ChunkEntry& entry, int level);

}  // namespace splat_lod::world
