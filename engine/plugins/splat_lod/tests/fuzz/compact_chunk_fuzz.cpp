// A streamed world's compressed chunk file (splat_lod/core/compact_chunk.h) two ways: read whole on its
// own (load_splat_file → world::read_compact_chunk_file: the header, the block table, every block's
// plane table and zstd frames, the quantisation ranges) and through world::read_chunk_range with the
// entry the generator would write for it (its prefix counts from the header, its checksums from the
// file's own bytes, so that mutations reach the decoder), for each stream level.
// Contract: either a cloud that keeps splat_io.h's promises (finite values, unit quaternions) with the
// header's count of Gaussians, and the stream levels read alone are the whole file's records; or an
// engine::Error naming the file.
#include <numeric>

#include "engine/core/error.h"
#include "splat_fuzz_support.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/compact_chunk.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/world_manifest.h"

namespace {

namespace sw = splat_lod::world;
using splat_fuzz::require;

// The entry of a file whose header parsed: counts from it, checksums of its bytes.
sw::ChunkEntry entry_for(std::span<const std::uint8_t> file) {
    const std::uint32_t blocks = sw::compact_chunk_block_count(file, "chunk");
    const std::uint64_t header_bytes = sw::kCompactChunkFixedHeaderBytes + 4ull * blocks;
    const sw::CompactChunkHeader header = sw::parse_compact_chunk_header(file.first(header_bytes), "chunk");
    sw::ChunkEntry e;
    e.codec = sw::ChunkCodec::compact;
    e.prefix_count = header.prefix_count;
    e.header_bytes = header_bytes;
    e.file_bytes = file.size();
    e.header_crc32 = sw::checksum(file.first(header_bytes));
    std::uint64_t at = header_bytes;
    for (const std::uint32_t size : header.block_bytes) {
        e.record_crc32.push_back(at + size <= file.size() ? sw::checksum(file.subspan(at, size)) : 0u);
        at += size;
    }
    return e;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> file(data, size);
    const std::filesystem::path path = splat_fuzz::sandbox_dir() / "chunk.splatc";
    splat_fuzz::write_file(path, file);
    splat_lod::LoadReport report;
    splat_lod::SplatCloud whole;
    try {
        whole = splat_lod::load_splat_file(path, &report);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, path.string());
        return 0;
    }
    splat_fuzz::check_cloud(whole, report);
    const sw::ChunkEntry entry = entry_for(file);  // parsed once already: cannot throw now
    require(whole.size() == entry.prefix_count[0], "the whole file holds the header's count");
    for (int level = sw::kLevels; level >= 1; --level) {
        const auto [begin, end] = sw::level_range(entry, level);
        const splat_lod::SplatCloud part = sw::read_chunk_range(path, entry, begin, end);
        require(part.size() == end - begin, "a stream level read alone holds its records");
        for (std::size_t i = 0; i < part.size(); ++i)
            require(part.positions[i] == whole.positions[begin + i] && part.sh_dc[i] == whole.sh_dc[begin + i] &&
                        part.opacity_logits[i] == whole.opacity_logits[begin + i],
                    "a stream level read alone is the whole file's records");
    }
    return 0;
}
