#pragma once
// A streamed world on disk: a grid of chunk files (baked LOD splat assets, ordered by stream level) and
// the glTF props placed on it, described by one manifest, `world.json`, written last and
// atomically by the generator (its presence means the world is complete). The streamer reads
// only the manifest up front; chunk files are read later, a stream-level prefix at a time.
//
// Stream levels (world/stream_levels.h): a chunk file holds its Gaussians ordered by stream level,
// 4 first, then 3, 2, 1, where a Gaussian's stream level says from how far it could be selected:
// stream level 4 is everything that can be drawn at any distance (the coarsest bake level, the
// large ground Gaussians), level 1 only what is needed close up (leaves, grass). `prefix_count[l − 1]`
// is the number of Gaussians with stream level ≥ l, so the chunk as needed from beyond the break
// of level l is the file's first prefix_count[l − 1] Gaussians, and prefix_count[0] is the whole file.
// Vertices are fixed-size records after the header: the bytes of a prefix are
// header_bytes + count · vertex_bytes. (Each Gaussian keeps its bake level, lod_level, which the
// renderer selects by; "level" in the streamer always means stream level.)
//
// Checksums (version 3): the manifest holds zlib's CRC-32 of each chunk file's header and of every
// block of its records, so that a reader finds a file that changed since the world was made even
// when its size, header and values still look right (a copy of another world's chunk, bit flips).
// Blocks never straddle a stream level: each stream level's records [prefix_count[l],
// prefix_count[l − 1]) are cut into blocks of kChecksumBlockRecords from its first record, the last
// block shorter (kCompactBlockRecords for compressed chunk files); record_crc32 lists them in file
// order (stream level 4 first). A read of one stream
// level or of a prefix therefore checks exactly the records it reads; any other range is widened to
// whole blocks (at most 2 · (kChecksumBlockRecords − 1) records more).
//
// Streaming decisions: stream level l < 4 of a chunk is needed only while, at the chunk's nearest
// distance z, some Gaussian of it could have coverage ≥ S_T or coverage / S_min ≥ S_rel_min. With
// coverage ≤ 2·e·f / z (e: the Gaussian's extent in world units, f: focal length in pixels) the
// per-level maxima below bound both tests, for any S_T and S_rel_min:
//   needed(l) ⇔ 2·extent_max·f / z ≥ S_T  or  2·extent_per_min_coverage_max·f / z ≥ S_rel_min.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/core/stream_levels.h"

namespace splat_lod::world {

// Version 4 adds chunk groups (world_groups.h), version 5 a chunk's codec; versions 3 (no groups) and
// 4 (every chunk a PLY file) still read.
inline constexpr int kManifestVersion = 5;
inline constexpr int kOldestManifestVersion = 3;
inline constexpr int kLevels = 4;
inline constexpr const char* kManifestFileName = "world.json";
inline constexpr std::uint64_t kChecksumBlockRecords = 1024;
inline constexpr std::uint64_t kCompactBlockRecords = 4096;

// How a chunk file stores its records. `ply`: a binary INRIA PLY, fixed-size records after its header
// (header_bytes + count · vertex_bytes), checksum blocks of kChecksumBlockRecords records. `compact`:
// compressed blocks of kCompactBlockRecords records after its header (compact_chunk.h); vertex_bytes
// is 0, the block sizes are in the header, and the record checksums are those of the compressed blocks.
enum class ChunkCodec { ply, compact };

struct ChunkLevel {
    // Largest extent sqrt(2·ln(255·o))·min(σ_max, √2·σ_mid) over the stream level's Gaussians
    // (world units; 0 for an empty level) and the largest ratio of that extent to the Gaussian's
    // coverage_min (−1 when some Gaussian of the level has none: always needed).
    float extent_max = 0.0f;
    float extent_per_min_coverage_max = 0.0f;
};

struct ChunkEntry {
    std::string id;              // "chunk_+003_-002": grid column and row, signed
    std::filesystem::path file;  // relative to the manifest's folder
    glm::ivec2 cell{0};          // grid column (x) and row (z)
    // A chunk of an imported capture may cover 2^span × 2^span grid cells where the capture is sparse
    // (world_import.h, "quadtree"): `cell` is then its lowest cell, aligned to 2^span in grid indices
    // (cell + count/2), and its parent in the quadtree is the group of depth span + 1. 0: one cell.
    int span = 0;
    glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};       // of the Gaussians' means, world space
    std::array<std::uint64_t, kLevels> prefix_count{};  // [l − 1]: Gaussians with stream level ≥ l
    std::array<ChunkLevel, kLevels> levels{};           // [l − 1]
    ChunkCodec codec = ChunkCodec::ply;
    std::uint64_t header_bytes = 0;
    std::uint64_t vertex_bytes = 0;           // bytes per Gaussian record in the file (ply; 0: compact)
    std::uint64_t file_bytes = 0;             // the whole file (checked before use)
    std::uint32_t header_crc32 = 0;           // CRC-32 of the header_bytes header bytes
    std::vector<std::uint32_t> record_crc32;  // one per record block (record_block_count), file order

    // Chunk groups only (world_groups.h): the quadtree depth (≥ 1; 0 for a chunk) and the pooling
    // cell (metres). A group's `cell` is its index at that depth.
    int depth = 0;
    float cell_m = 0.0f;

    // The PLY file's bytes down to `level` (codec ply only).
    std::uint64_t prefix_bytes(int level) const { return header_bytes + prefix_count[level - 1] * vertex_bytes; }
    // Records per checksum block: kChecksumBlockRecords (ply) or kCompactBlockRecords (compact).
    std::uint64_t block_records() const {
        return codec == ChunkCodec::compact ? kCompactBlockRecords : kChecksumBlockRecords;
    }
    // The bytes `count` records take on disk: exact for ply, the file's mean for compact.
    std::uint64_t disk_bytes(std::uint64_t count) const {
        if (codec == ChunkCodec::ply || prefix_count[0] == 0) return count * vertex_bytes;
        return (file_bytes - header_bytes) * count / prefix_count[0];
    }
};

struct Prop {
    std::filesystem::path mesh;  // a glTF file, relative to the manifest's folder
    glm::vec3 translation{0.0f};
    glm::vec3 rotation_euler_deg{0.0f};
    glm::vec3 scale{1.0f};
};

// The ground under an imported capture (world_import.h): a height per cell of a `cells` × `cells`
// grid over the world's square (rows of increasing z, each of increasing x), where a game walks and
// measures its height above the ground. Generated worlds compute theirs from the terrain and have none.
struct GroundGrid {
    int cells = 0;
    std::vector<float> heights;
    bool empty() const { return cells == 0; }
    // The height of the cell holding (x, z), clamped to the grid, for a world of `size_m`.
    float height(float x, float z, float size_m) const;
};

// Where an imported world came from: the capture as named, and the rigid map from the capture's frame
// to the world's (p_world = rotation · p_capture + translation), so that users can place meshes
// authored against the capture.
struct CaptureOrigin {
    std::string source;
    std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major
    std::array<double, 3> translation{};
    bool empty() const { return source.empty(); }
};

struct WorldManifest {
    int version = kManifestVersion;
    std::uint64_t seed = 1;
    float size_m = 1024.0f;  // the world spans [−size/2, size/2] in x and z
    float chunk_size_m = 64.0f;
    // The scale of a generated world's river and path (world_terrain.h, "the feature scale"), at most
    // size_m; 0 stands for size_m. The file has it only where it is less than size_m: every world
    // generated before larger worlds kept the scale of their middle has the scale of its size.
    float feature_m = 0.0f;
    float feature_scale() const { return feature_m > 0.0f ? feature_m : size_m; }
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    std::uint64_t gaussians = 0;  // over all chunks
    // What the world was made with beyond seed and sizes: the Gaussian count scale and the
    // generator's content and bake settings. A cached world is reused only when both are equal.
    float density = 1.0f;
    std::string generator;
    StreamLevelRule stream_levels;  // how the chunk files were split into stream levels
    std::vector<ChunkEntry> chunks;
    // The chunk groups (world_groups.h), depth 1 first; every Gaussian of a group is of stream level 4.
    // `group_generator` says how they were pooled (empty when the world has none).
    std::vector<ChunkEntry> groups;
    std::string group_generator;
    std::vector<Prop> props;
    std::filesystem::path terrain_mesh;  // optional glTF ground under the splats (may be empty)
    GroundGrid ground;                   // imported worlds only (may be empty)
    CaptureOrigin capture;               // imported worlds only (may be empty)
};

// A block of records covered by one checksum: records [begin, end), record_crc32[index].
struct RecordBlock {
    std::uint64_t begin = 0, end = 0;
    std::size_t index = 0;
};

// The checksum the manifest records of a header or a record block: zlib's CRC-32 of the bytes.
std::uint32_t checksum(std::span<const std::uint8_t> bytes);

// A checksum of everything the manifest says but its chunk groups and its version: what a render
// with every chunk resident and no group depends on (the chunks' bytes through their checksums, the
// props, the terrain mesh, the settings). New groups or a version-3 manifest rewritten as version 4
// keep it.
std::uint32_t chunks_checksum(const WorldManifest& manifest);

// How many record blocks the entry's prefix counts make (what record_crc32 must hold).
std::uint64_t record_block_count(const ChunkEntry& entry);
// The blocks that hold a record of [begin, end), in file order (none for an empty range). The
// range must lie within [0, prefix_count[0]] and the prefix counts must not grow with the level.
std::vector<RecordBlock> record_blocks(const ChunkEntry& entry, std::uint64_t begin, std::uint64_t end);

// "chunk_+003_-002" for column 3, row −2.
std::string chunk_id(const glm::ivec2& cell);

// Reads and checks a manifest. Every problem throws engine::Error as "<file>: <key path>: <problem>"
// ("world.json: chunks[3].prefix_count: counts must not increase with the level"): a missing or
// unreadable file, bad JSON, another version, an unknown or missing key, a wrong type, a negative
// or non-finite number, prefix counts that grow with the level or disagree with the byte counts,
// checksums that are not 32-bit or not one per record block, and paths (chunk files, meshes) that
// are absolute or leave the manifest's folder.
WorldManifest read_world_manifest(const std::filesystem::path& path);
// The same from text already in memory; `name` is the file named in error messages.
WorldManifest parse_world_manifest(const std::string& text, const std::string& name);

// Writes the manifest through a temporary file and a rename (engine::write_file_atomic): a reader
// sees the old manifest or the new one, never a part. Checks the same rules as the reader first.
// Always writes version kManifestVersion (a manifest read as version 3 has no groups, which version 4
// allows).
void write_world_manifest(const std::filesystem::path& path, const WorldManifest& manifest);

// The manifest entry of a baked chunk already written to `folder / file` (an INRIA PLY by
// write_inria_ply): prefix counts (the cloud must be in stream_order() of `rule`: stream level 4
// first), bounds of the means, per-stream-level extent bounds (world/gaussian_extent.h), the byte
// layout read back from the file's header and the checksums of the bytes read back from the file
// (so that what the manifest vouches for is what reached the disk). Throws engine::Error naming the
// file when the order is wrong or the file does not hold the cloud's records.
ChunkEntry describe_chunk(const SplatCloud& baked, const std::filesystem::path& folder,
                          const std::filesystem::path& file, const glm::ivec2& cell, const StreamLevelRule& rule);

}  // namespace splat_lod::world
