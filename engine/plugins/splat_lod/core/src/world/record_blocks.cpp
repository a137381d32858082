// The checksum and the record blocks of a chunk file (world_manifest.h: checksums): blocks of
// ChunkEntry::block_records() records that restart at every stream level.
#include <algorithm>
#include <array>
#include <string>

#include <zlib.h>

#include "engine/core/error.h"
#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {
namespace {

// The stream levels' record ranges in file order (stream level 4 first): [starts[k], starts[k + 1]).
std::array<std::uint64_t, kLevels + 1> level_starts(const ChunkEntry& entry) {
    std::array<std::uint64_t, kLevels + 1> starts{};
    for (int k = 1; k <= kLevels; ++k)
        starts[static_cast<std::size_t>(k)] = entry.prefix_count[static_cast<std::size_t>(kLevels - k)];
    return starts;
}

std::uint64_t blocks_of(std::uint64_t records, std::uint64_t block) {
    return records / block + (records % block != 0 ? 1 : 0);
}

}  // namespace

std::uint32_t checksum(std::span<const std::uint8_t> bytes) {
    return static_cast<std::uint32_t>(crc32_z(crc32_z(0, Z_NULL, 0), bytes.data(), bytes.size()));
}

std::uint64_t record_block_count(const ChunkEntry& entry) {
    const auto starts = level_starts(entry);
    std::uint64_t count = 0;
    for (int k = 0; k < kLevels; ++k) {
        const std::uint64_t begin = starts[static_cast<std::size_t>(k)], end = starts[static_cast<std::size_t>(k + 1)];
        if (end > begin) count += blocks_of(end - begin, entry.block_records());
    }
    return count;
}

std::vector<RecordBlock> record_blocks(const ChunkEntry& entry, std::uint64_t begin, std::uint64_t end) {
    const auto starts = level_starts(entry);
    if (begin > end || end > entry.prefix_count[0] || !std::is_sorted(starts.begin(), starts.end()))
        engine::fail("splat_lod::world::record_blocks(): records [" + std::to_string(begin) + ", " +
                     std::to_string(end) + ") are not within the chunk's " + std::to_string(entry.prefix_count[0]) +
                     " records or its prefix counts grow with the level");
    std::vector<RecordBlock> blocks;
    std::uint64_t index = 0;
    const std::uint64_t size = entry.block_records();
    for (int k = 0; k < kLevels && begin < end; ++k) {
        const std::uint64_t first = starts[static_cast<std::size_t>(k)], last = starts[static_cast<std::size_t>(k + 1)];
        if (last > first && begin < last && end > first) {
            const std::uint64_t from = (std::max(begin, first) - first) / size;
            const std::uint64_t to = (std::min(end, last) - first - 1) / size;
            for (std::uint64_t b = from; b <= to; ++b)
                blocks.push_back(
                    {first + b * size, std::min(last, first + (b + 1) * size), static_cast<std::size_t>(index + b)});
        }
        if (last > first) index += blocks_of(last - first, size);
    }
    return blocks;
}

}  // namespace splat_lod::world
