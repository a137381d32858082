// Reading a range of a chunk's records (world/chunk_reader.h): for a PLY file the header is read and
// checked against the manifest entry and its checksum, then only the checksum blocks that hold the
// wanted records, which are checked and decoded by the ordinary PLY reader behind a header rewritten
// to their count (one decoder for whole files and ranges). Compressed files: compact_chunk_file.cpp.
#include "splat_lod/core/chunk_reader.h"

#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "splat_lod/core/ply_vertex_layout.h"
#include "splat_lod/core/splat_io.h"
#include "world/chunk_description.h"

namespace splat_lod::world {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& message) {
    engine::fail(file.string() + ": " + message);
}

void check_layout(const std::filesystem::path& file, const ChunkEntry& entry, const io::PlyVertexLayout& layout) {
    if (layout.file_bytes != entry.file_bytes)
        fail(file, "is " + std::to_string(layout.file_bytes) + " bytes but the manifest says " +
                       std::to_string(entry.file_bytes) + " (changed or truncated since the world was generated)");
    if (layout.header_bytes != entry.header_bytes || layout.vertex_bytes != entry.vertex_bytes ||
        layout.vertex_count != entry.prefix_count[0])
        fail(file, "header differs from the manifest: " + std::to_string(layout.vertex_count) + " records of " +
                       std::to_string(layout.vertex_bytes) + " bytes after " + std::to_string(layout.header_bytes) +
                       " header bytes, expected " + std::to_string(entry.prefix_count[0]) + " of " +
                       std::to_string(entry.vertex_bytes) + " after " + std::to_string(entry.header_bytes));
    // With the size checked against its own header, a range can never ask for more than the file.
    std::uint64_t records = 0, expected = 0;
    if (__builtin_mul_overflow(layout.vertex_count, layout.vertex_bytes, &records) ||
        __builtin_add_overflow(records, layout.header_bytes, &expected) || expected != layout.file_bytes)
        fail(file, "is " + std::to_string(layout.file_bytes) + " bytes but its header describes " +
                       std::to_string(layout.vertex_count) + " records of " + std::to_string(layout.vertex_bytes) +
                       " bytes (truncated or with trailing bytes)");
}

}  // namespace

SplatCloud read_chunk_range(const std::filesystem::path& file, const ChunkEntry& entry, std::uint64_t begin,
                            std::uint64_t end) {
    if (begin > end || end > entry.prefix_count[0])
        fail(file, "records [" + std::to_string(begin) + ", " + std::to_string(end) + ") are outside the chunk's " +
                       std::to_string(entry.prefix_count[0]));
    if (entry.record_crc32.size() != record_block_count(entry))
        fail(file, "the manifest entry has " + std::to_string(entry.record_crc32.size()) +
                       " record checksums, expected " + std::to_string(record_block_count(entry)));
    if (entry.codec == ChunkCodec::compact) return read_compact_chunk_range(file, entry, begin, end);
    const io::PlyVertexLayout layout = io::read_ply_vertex_layout(file);
    check_layout(file, entry, layout);
    if (checksum(std::span(reinterpret_cast<const std::uint8_t*>(layout.header.data()), layout.header.size())) !=
        entry.header_crc32)
        fail(file, "header does not match the manifest's checksum (the file changed since the world was generated)");

    // The records of every checksum block that holds one of [begin, end), read after room for a header.
    const std::vector<RecordBlock> blocks = record_blocks(entry, begin, end);
    const std::uint64_t first = blocks.empty() ? begin : blocks.front().begin;
    const std::uint64_t last = blocks.empty() ? end : blocks.back().end;
    const std::uint64_t offset = layout.header_bytes + first * layout.vertex_bytes;
    const std::uint64_t size = (last - first) * layout.vertex_bytes;
    const std::string header = io::header_with_vertex_count(layout, end - begin);
    std::vector<std::uint8_t> bytes(header.size() + static_cast<std::size_t>(size));
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(file, "cannot open");
    in.seekg(static_cast<std::streamoff>(offset));
    std::uint8_t* const records = bytes.data() + header.size();
    in.read(reinterpret_cast<char*>(records), static_cast<std::streamsize>(size));
    if (static_cast<std::uint64_t>(in.gcount()) != size)
        fail(file, "offset " + std::to_string(offset) + ": the file ends before record " + std::to_string(last) +
                       " (truncated)");
    for (const RecordBlock& block : blocks) {
        const std::uint8_t* at = records + (block.begin - first) * layout.vertex_bytes;
        if (checksum(std::span(at, static_cast<std::size_t>((block.end - block.begin) * layout.vertex_bytes))) !=
            entry.record_crc32[block.index])
            fail(file, "records [" + std::to_string(block.begin) + ", " + std::to_string(block.end) +
                           ") do not match the manifest's checksum (the file changed since the world was generated)");
    }

    // The wanted records with the rewritten header just before them (over checked bytes of the
    // block before `begin`, or in the room left for it), decoded by the ordinary reader.
    std::uint8_t* const wanted = records + (begin - first) * layout.vertex_bytes;
    std::copy(header.begin(), header.end(), wanted - header.size());
    const std::span<const std::uint8_t> ply(
        wanted - header.size(), header.size() + static_cast<std::size_t>((end - begin) * layout.vertex_bytes));
    const std::string range = "records [" + std::to_string(begin) + ", " + std::to_string(end) + ")";
    LoadReport report;
    SplatCloud cloud;
    try {
        cloud = read_ply(ply, file.string(), &report);
    } catch (const engine::Error& e) {
        // "<file>: <problem>" from the reader, said again with the range: "<file>: records [b, e): <problem>".
        const std::string message = e.what(), prefix = file.string() + ": ";
        fail(file, range + ": " + (message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message));
    }
    // A dropped record would shift every later index: a chunk's records must all be usable.
    if (report.dropped() > 0)
        fail(file, range + ": " + std::to_string(report.dropped()) + " have NaN/Inf values or a zero quaternion");
    return cloud;
}

std::pair<std::uint64_t, std::uint64_t> level_range(const ChunkEntry& entry, int level) {
    if (level < 1 || level > kLevels) engine::fail("splat_lod::world::level_range(): level must be 1..4");
    const std::uint64_t begin = level == kLevels ? 0 : entry.prefix_count[static_cast<std::size_t>(level)];
    return {begin, entry.prefix_count[static_cast<std::size_t>(level - 1)]};
}

SplatCloud read_chunk_prefix(const std::filesystem::path& file, const ChunkEntry& entry, int level) {
    if (level < 1 || level > kLevels) engine::fail("splat_lod::world::read_chunk_prefix(): level must be 1..4");
    return read_chunk_range(file, entry, 0, entry.prefix_count[static_cast<std::size_t>(level - 1)]);
}

}  // namespace splat_lod::world
