// A streamed world's chunk file through world::read_chunk_range (splat_lod/core/chunk_reader.h),
// the streamer's reader: the header layout (io::read_ply_vertex_layout), the size, header and
// checksum checks against the manifest entry, the widened block read and the decode behind a
// rewritten header.
// Input: byte 0 selects what the manifest entry gets wrong (bit 0: the header's CRC, bit 1: the
// CRC of one record block, chosen by byte 6; bit 2: the record count, one too many); bytes 1–3
// split the records into stream levels, bytes 4–5 choose an extra range; the rest is the chunk
// file. The entry is what the generator would write for a chunk of that layout (world_manifest.h),
// its checksums computed from the file's own bytes, so that mutations reach the decoder and not
// only the size check.
// Contract: read_chunk_range either returns exactly end − begin Gaussians keeping splat_io.h's
// promises, or throws engine::Error naming the file; it never returns records from a block whose
// checksum is wrong, nor from a file whose header checksum is wrong.
#include <algorithm>
#include <array>

#include "engine/core/error.h"
#include "splat_fuzz_support.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/ply_vertex_layout.h"
#include "splat_lod/core/world_manifest.h"

namespace {

namespace sw = splat_lod::world;
using splat_fuzz::require;

constexpr std::size_t kControlBytes = 7;

// The entry the generator would describe for a file with this layout; prefix counts split by the
// control bytes; checksums of the bytes the file holds (0 for blocks past its end).
sw::ChunkEntry entry_for(const splat_lod::io::PlyVertexLayout& layout, std::span<const std::uint8_t> file,
                         const std::uint8_t* control) {
    sw::ChunkEntry e;
    e.id = "chunk_+000_+000";
    e.file = "chunk.lod.ply";
    // A header claiming more records than the file could hold would make a manifest of that many
    // checksums; the generator never writes one, so the entry holds what the bytes can.
    const std::uint64_t fit = layout.vertex_bytes == 0 ? 0 : (file.size() - layout.header_bytes) / layout.vertex_bytes;
    const std::uint64_t n = std::min<std::uint64_t>(layout.vertex_count, fit + 1) + ((control[0] & 4u) ? 1 : 0);
    e.prefix_count[0] = n;
    for (std::size_t l = 1; l < sw::kLevels; ++l)
        e.prefix_count[l] = e.prefix_count[l - 1] * control[l] / 255;  // non-increasing by construction
    e.header_bytes = layout.header_bytes;
    e.vertex_bytes = std::max<std::uint64_t>(layout.vertex_bytes, 1);
    e.file_bytes = e.prefix_bytes(1);
    e.header_crc32 = sw::checksum(file.first(static_cast<std::size_t>(layout.header_bytes)));
    for (const sw::RecordBlock& block : sw::record_blocks(e, 0, n)) {
        const std::uint64_t from = e.header_bytes + block.begin * e.vertex_bytes;
        const std::uint64_t to = e.header_bytes + block.end * e.vertex_bytes;
        const bool present = to <= file.size();
        const auto size = static_cast<std::size_t>(to - from);
        e.record_crc32.push_back(present ? sw::checksum(file.subspan(static_cast<std::size_t>(from), size)) : 0);
    }
    return e;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < kControlBytes) return 0;
    const std::uint8_t* control = data;
    const std::span<const std::uint8_t> file(data + kControlBytes, size - kControlBytes);
    const std::filesystem::path path = splat_fuzz::sandbox_dir() / "chunk.lod.ply";
    splat_fuzz::write_file(path, file);

    splat_lod::io::PlyVertexLayout layout;
    try {
        layout = splat_lod::io::read_ply_vertex_layout(path);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, path.string());
        return 0;
    }
    require(layout.header_bytes == layout.header.size() && layout.header_bytes <= file.size() &&
                layout.file_bytes == file.size(),
            "the layout describes the file's header and size");
    sw::ChunkEntry entry = entry_for(layout, file, control);
    const bool header_wrong = (control[0] & 1u) != 0;
    if (header_wrong) entry.header_crc32 ^= 0x80000000u;
    std::size_t wrong_block = entry.record_crc32.size();
    if ((control[0] & 2u) && !entry.record_crc32.empty()) {
        wrong_block = control[6] % entry.record_crc32.size();
        entry.record_crc32[wrong_block] ^= 1u;
    }

    const std::uint64_t n = entry.prefix_count[0];
    std::vector<std::pair<std::uint64_t, std::uint64_t>> ranges;
    for (int l = sw::kLevels; l >= 1; --l) ranges.push_back(sw::level_range(entry, l));
    const std::uint64_t a = n * control[4] / 255, b = n * control[5] / 255;
    ranges.push_back({std::min(a, b), std::max(a, b)});
    for (const auto& [begin, end] : ranges) {
        splat_lod::SplatCloud cloud;
        try {
            cloud = sw::read_chunk_range(path, entry, begin, end);
        } catch (const engine::Error& e) {
            splat_fuzz::check_error_names(e, path.string());
            continue;
        }
        require(cloud.size() == end - begin, "a range read returns exactly its records");
        splat_lod::LoadReport report;
        report.gaussians_in_file = report.loaded = cloud.size();
        splat_fuzz::check_cloud(cloud, report);
        require(!header_wrong, "a read succeeded although the header's checksum is wrong");
        for (const sw::RecordBlock& block : sw::record_blocks(entry, begin, end))
            require(block.index != wrong_block, "a read succeeded through a block whose checksum is wrong");
    }
    return 0;
}
