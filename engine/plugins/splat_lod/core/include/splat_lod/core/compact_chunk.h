#pragma once
// Compressed chunk files (codec "compact" of world_manifest.h): a world chunk's Gaussians as the
// compact records of the GPU scene (compact_gaussians.h), in blocks that are each compressed with
// zstd on their own, so that a reader decompresses only the blocks of the stream levels it loads and
// a corrupt block is found by its checksum before it is decoded.
//
// The file, little-endian:
//   bytes 0–7    the magic "SPLATCZ1"
//   bytes 8–11   the format version (kCompactChunkVersion)
//   bytes 12–15  the SH degree of the records (0..3)
//   bytes 16–23  the Gaussian count
//   bytes 24–27  records per block (kCompactBlockRecords)
//   bytes 28–31  the block count B
//   bytes 32–63  the prefix counts (world_manifest.h: Gaussians with stream level ≥ 1, 2, 3, 4)
//   then B × 4   each block's compressed bytes, file order
//   then the B blocks, back to back.
// The file describes itself (load_splat_file() reads one whole, without its world); the manifest's
// entry repeats the counts and adds the checksums. The blocks are the manifest's record blocks (world_manifest.h: one
// per kCompactBlockRecords records of a stream level, never straddling two), so the manifest's record_crc32 are the
// CRC-32s of these compressed blocks and a stream level reads whole blocks only.
//
// A block of n records is the CompactPage its records are quantised against (19 floats,
// compact_gaussians.h), a table of P 32-bit plane sizes, then P zstd frames, one per plane. A plane holds
// one byte of one field for all n records: the fields of the 160-bit record (x, y, z, opacity, the three
// log-scales, the rotation's four bytes, red, green, blue, level, coverage_min, coverage_max) and each
// byte of the SH words, low byte first for fields over 8 bits. Before the split, x, y and z are stored
// as the difference from the record before (the bake keeps neighbours together) and coverage_max as
// the difference from the record's coverage_min, each modulo 2^bits. A frame per plane gives each
// field its own entropy table: the default world's chunks take 15.7 bytes a Gaussian at SH 0, where the
// same planes in one frame per block took about 17 (docs/gpu_storage.md). zstd level 3: higher levels
// gain a few percent and cost the generator more time than it writes PLY files in.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::world {

// Version 2 stores the higher SH bands as compact_gaussians.h does now; version 1 (still read) stored
// a byte per coefficient, (byte − 128)·step, with each band's step where version 2 keeps its largest
// magnitude. Both are the same at SH degree 0.
inline constexpr std::uint32_t kCompactChunkVersion = 2;
inline constexpr std::size_t kCompactChunkFixedHeaderBytes = 64;
inline constexpr int kCompactChunkZstdLevel = 3;

struct CompactChunkHeader {
    std::uint32_t version = kCompactChunkVersion;  // what is read; the writer writes kCompactChunkVersion
    int sh_degree = 0;
    std::uint64_t count = 0;
    std::array<std::uint64_t, 4> prefix_count{};  // as ChunkEntry::prefix_count
    std::vector<std::uint32_t> block_bytes;       // compressed size of each block, file order

    std::uint64_t header_bytes() const { return kCompactChunkFixedHeaderBytes + 4 * block_bytes.size(); }
};

std::vector<std::uint8_t> encode_compact_chunk_header(const CompactChunkHeader& header);
// The fixed part's block count, to know how many header bytes to read: throws engine::Error naming
// `name` when the bytes are fewer than the fixed part or the magic or version is not this format's.
std::uint32_t compact_chunk_block_count(std::span<const std::uint8_t> fixed, const std::string& name);
// The whole header (fixed part and block table); the same errors, and for an SH degree over 3, a
// block size other than kCompactBlockRecords, prefix counts that grow with the level or whose first
// is not the count, or bytes that are not exactly the header.
CompactChunkHeader parse_compact_chunk_header(std::span<const std::uint8_t> bytes, const std::string& name);

// Records [first, first + count) of `cloud` (with its lod attributes, SH up to its degree) as one
// block, quantised against ranges fitted to them (fit_compact_page). Every Gaussian must be drawable
// (compact_gaussians.h: gaussian_is_drawable); engine::Error otherwise.
std::vector<std::uint8_t> encode_compact_chunk_block(const SplatCloud& cloud, std::size_t first, std::size_t count);

// Decodes a block of `count` records of a file with `header` (its version and SH degree) into
// out[at, at + count) (out sized, with lod attributes and the header's SH degree). Throws engine::Error naming `name`
// when the block does not decompress to exactly the expected bytes, its plane table does not add up to its size, or its
// ranges are not finite.
void decode_compact_chunk_block(std::span<const std::uint8_t> block, std::size_t count,
                                const CompactChunkHeader& header, SplatCloud& out, std::size_t at,
                                const std::string& name);

// A compressed chunk file read whole on its own (no manifest, so no checksums: the blocks must decode
// and add up to the file's size). Throws engine::Error naming the file.
SplatCloud read_compact_chunk_file(const std::filesystem::path& path, LoadReport* report = nullptr);

}  // namespace splat_lod::world
