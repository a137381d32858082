// Reading a range of a chunk's records (world/chunk_reader.h): the header is read and checked
// against the manifest entry, then only the wanted records, which are decoded by the ordinary PLY
// reader behind a header rewritten to their count (one decoder for whole files and ranges).
#include "splat_lod/world/chunk_reader.h"

#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "io/ply_vertex_layout.h"
#include "splat_lod/splat_io.h"

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
    const io::PlyVertexLayout layout = io::read_ply_vertex_layout(file);
    check_layout(file, entry, layout);

    const std::string header = io::header_with_vertex_count(layout, end - begin);
    const std::uint64_t offset = layout.header_bytes + begin * layout.vertex_bytes;
    const std::uint64_t size = (end - begin) * layout.vertex_bytes;
    std::vector<std::uint8_t> bytes(header.size() + static_cast<std::size_t>(size));
    std::copy(header.begin(), header.end(), bytes.begin());
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(file, "cannot open");
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(reinterpret_cast<char*>(bytes.data() + header.size()), static_cast<std::streamsize>(size));
    if (static_cast<std::uint64_t>(in.gcount()) != size)
        fail(file, "offset " + std::to_string(offset) + ": the file ends before record " + std::to_string(end) +
                       " (truncated)");

    LoadReport report;
    SplatCloud cloud = read_ply(bytes, file.string() + " [" + std::to_string(begin) + ", " + std::to_string(end) + ")",
                                &report);
    // A dropped record would shift every later index: a chunk's records must all be usable.
    if (report.dropped() > 0)
        fail(file, std::to_string(report.dropped()) + " records in [" + std::to_string(begin) + ", " +
                       std::to_string(end) + ") have NaN/Inf values or a zero quaternion");
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
