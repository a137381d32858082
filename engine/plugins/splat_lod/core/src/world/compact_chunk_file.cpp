// Compressed chunk files on disk (compact_chunk.h): the writer behind write_chunk_file() and the
// reader behind read_chunk_range() for codec "compact", and where each record block lies in a file.
#include <fstream>
#include <numeric>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/chunk_writer.h"
#include "splat_lod/core/compact_chunk.h"
#include "splat_lod/core/splat_io.h"
#include "world/chunk_description.h"

namespace splat_lod::world {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& message) {
    engine::fail(file.string() + ": " + message);
}

std::string range_text(std::uint64_t begin, std::uint64_t end) {
    return "records [" + std::to_string(begin) + ", " + std::to_string(end) + ")";
}

// The header read from `in` and checked against the entry: its checksum, count, blocks and size.
CompactChunkHeader read_checked_header(std::ifstream& in, const std::filesystem::path& file, const ChunkEntry& entry) {
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(entry.header_bytes));
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (static_cast<std::uint64_t>(in.gcount()) != entry.header_bytes) fail(file, "ends inside its header (truncated)");
    if (checksum(bytes) != entry.header_crc32)
        fail(file, "header does not match the manifest's checksum (the file changed since the world was generated)");
    const CompactChunkHeader header = parse_compact_chunk_header(bytes, file.string());
    const std::uint64_t blocks =
        std::accumulate(header.block_bytes.begin(), header.block_bytes.end(), std::uint64_t{0});
    if (header.prefix_count != entry.prefix_count || header.block_bytes.size() != entry.record_crc32.size() ||
        header.header_bytes() + blocks != entry.file_bytes)
        fail(file, "header describes " + std::to_string(header.count) + " records in " +
                       std::to_string(header.block_bytes.size()) + " blocks, " +
                       std::to_string(header.header_bytes() + blocks) + " bytes; the manifest " +
                       std::to_string(entry.prefix_count[0]) + " in " + std::to_string(entry.record_crc32.size()) +
                       ", " + std::to_string(entry.file_bytes));
    return header;
}

std::ifstream open_checked(const std::filesystem::path& file, const ChunkEntry& entry) {
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(file, ec);
    if (ec) fail(file, "cannot read (" + ec.message() + ")");
    if (size != entry.file_bytes)
        fail(file, "is " + std::to_string(size) + " bytes but the manifest says " + std::to_string(entry.file_bytes) +
                       " (changed or truncated since the world was generated)");
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(file, "cannot open");
    return in;
}

std::vector<BlockBytes> block_extents(const CompactChunkHeader& header) {
    std::vector<BlockBytes> out;
    std::uint64_t at = header.header_bytes();
    for (const std::uint32_t size : header.block_bytes) {
        out.push_back({at, size});
        at += size;
    }
    return out;
}

// Every block of a whole file's bytes (its header parsed, the entry's prefix counts set).
SplatCloud decode_whole(std::span<const std::uint8_t> bytes, const CompactChunkHeader& header, const ChunkEntry& entry,
                        const std::string& name) {
    SplatCloud cloud;
    cloud.set_sh_degree(header.sh_degree);
    cloud.resize(static_cast<std::size_t>(header.count));
    const std::vector<BlockBytes> extents = block_extents(header);
    for (const RecordBlock& block : record_blocks(entry, 0, header.count)) {
        const BlockBytes& at = extents[block.index];
        decode_compact_chunk_block(bytes.subspan(static_cast<std::size_t>(at.offset), at.size),
                                   static_cast<std::size_t>(block.end - block.begin), header, cloud,
                                   static_cast<std::size_t>(block.begin),
                                   name + ": " + range_text(block.begin, block.end));
    }
    return cloud;
}

}  // namespace

SplatCloud read_compact_chunk_range(const std::filesystem::path& file, const ChunkEntry& entry, std::uint64_t begin,
                                    std::uint64_t end) {
    std::ifstream in = open_checked(file, entry);
    const CompactChunkHeader header = read_checked_header(in, file, entry);
    const std::vector<BlockBytes> extents = block_extents(header);
    const std::vector<RecordBlock> blocks = record_blocks(entry, begin, end);
    SplatCloud cloud;
    cloud.set_sh_degree(header.sh_degree);
    if (blocks.empty()) return cloud;
    const std::uint64_t first = blocks.front().begin, last = blocks.back().end;
    const std::uint64_t offset = extents[blocks.front().index].offset;
    std::vector<std::uint8_t> bytes(
        static_cast<std::size_t>(extents[blocks.back().index].offset + extents[blocks.back().index].size - offset));
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (static_cast<std::uint64_t>(in.gcount()) != bytes.size())
        fail(file, "offset " + std::to_string(offset) + ": the file ends before record " + std::to_string(last) +
                       " (truncated)");
    cloud.resize(static_cast<std::size_t>(last - first));
    for (const RecordBlock& block : blocks) {
        const BlockBytes& at = extents[block.index];
        const std::span<const std::uint8_t> data(bytes.data() + (at.offset - offset),
                                                 static_cast<std::size_t>(at.size));
        if (checksum(data) != entry.record_crc32[block.index])
            fail(file, range_text(block.begin, block.end) +
                           " do not match the manifest's checksum (the file changed since the world was generated)");
        decode_compact_chunk_block(data, static_cast<std::size_t>(block.end - block.begin), header, cloud,
                                   static_cast<std::size_t>(block.begin - first),
                                   file.string() + ": " + range_text(block.begin, block.end));
    }
    if (begin == first && end == last) return cloud;
    std::vector<std::uint32_t> wanted(static_cast<std::size_t>(end - begin));
    std::iota(wanted.begin(), wanted.end(), static_cast<std::uint32_t>(begin - first));
    return cloud.permuted(wanted);
}

SplatCloud read_compact_chunk_file(const std::filesystem::path& path, LoadReport* report) {
    const std::vector<std::uint8_t> bytes = engine::read_binary_file(path);
    const std::string name = path.string();
    const std::uint32_t blocks = compact_chunk_block_count(bytes, name);
    const std::uint64_t header_bytes = kCompactChunkFixedHeaderBytes + 4ull * blocks;
    if (bytes.size() < header_bytes) fail(path, "ends inside its header's block table (truncated)");
    const CompactChunkHeader header = parse_compact_chunk_header(std::span(bytes).first(header_bytes), name);
    ChunkEntry entry;
    entry.codec = ChunkCodec::compact;
    entry.prefix_count = header.prefix_count;
    entry.header_bytes = header_bytes;
    const std::uint64_t body = std::accumulate(header.block_bytes.begin(), header.block_bytes.end(), std::uint64_t{0});
    if (record_block_count(entry) != blocks || header_bytes + body != bytes.size())
        fail(path, "header describes " + std::to_string(blocks) + " blocks of " + std::to_string(header_bytes + body) +
                       " bytes in all; the file is " + std::to_string(bytes.size()) + " bytes and its counts make " +
                       std::to_string(record_block_count(entry)) + " blocks");
    SplatCloud cloud = decode_whole(bytes, header, entry, name);
    if (report) {
        *report = LoadReport{};
        report->format = "compressed world chunk";
        report->gaussians_in_file = report->loaded = cloud.size();
    }
    return cloud;
}

std::vector<BlockBytes> record_block_bytes(const std::filesystem::path& file, const ChunkEntry& entry) {
    if (entry.codec == ChunkCodec::compact) {
        std::ifstream in = open_checked(file, entry);
        return block_extents(read_checked_header(in, file, entry));
    }
    std::vector<BlockBytes> out;
    for (const RecordBlock& block : record_blocks(entry, 0, entry.prefix_count[0]))
        out.push_back(
            {entry.header_bytes + block.begin * entry.vertex_bytes, (block.end - block.begin) * entry.vertex_bytes});
    return out;
}

ChunkEntry write_chunk_file(const SplatCloud& ordered, const std::filesystem::path& folder,
                            const std::filesystem::path& file, const glm::ivec2& cell, const StreamLevelRule& rule,
                            ChunkCodec codec) {
    const std::filesystem::path path = folder / file;
    if (codec == ChunkCodec::ply) {
        write_inria_ply(path, ordered);
        return describe_chunk(ordered, folder, file, cell, rule);
    }
    std::vector<std::uint8_t> stream;
    ChunkEntry entry = describe_records(ordered, file, cell, rule, path.string(), stream);
    entry.codec = ChunkCodec::compact;
    const std::vector<RecordBlock> blocks = record_blocks(entry, 0, entry.prefix_count[0]);
    CompactChunkHeader header;
    header.sh_degree = ordered.sh_degree;
    header.count = ordered.size();
    header.prefix_count = entry.prefix_count;
    std::vector<std::uint8_t> body;
    for (const RecordBlock& block : blocks) {
        std::vector<std::uint8_t> encoded;
        try {
            encoded = encode_compact_chunk_block(ordered, static_cast<std::size_t>(block.begin),
                                                 static_cast<std::size_t>(block.end - block.begin));
        } catch (const engine::Error& e) {
            fail(path, e.what());
        }
        header.block_bytes.push_back(static_cast<std::uint32_t>(encoded.size()));
        body.insert(body.end(), encoded.begin(), encoded.end());
    }
    std::vector<std::uint8_t> bytes = encode_compact_chunk_header(header);
    bytes.insert(bytes.end(), body.begin(), body.end());
    engine::write_file_atomic(path, bytes);

    // What the manifest vouches for is what reached the disk: checksums of the bytes read back.
    const std::vector<std::uint8_t> disk = engine::read_binary_file(path);
    if (disk.size() != bytes.size())
        fail(path, "is " + std::to_string(disk.size()) + " bytes after writing " + std::to_string(bytes.size()));
    entry.header_bytes = header.header_bytes();
    entry.vertex_bytes = 0;
    entry.file_bytes = disk.size();
    const std::span<const std::uint8_t> all(disk);
    entry.header_crc32 = checksum(all.first(static_cast<std::size_t>(entry.header_bytes)));
    for (const BlockBytes& at : block_extents(header))
        entry.record_crc32.push_back(checksum(all.subspan(static_cast<std::size_t>(at.offset), at.size)));
    widen_bounds(entry, decode_whole(all, header, entry, path.string()), stream);
    return entry;
}

}  // namespace splat_lod::world
