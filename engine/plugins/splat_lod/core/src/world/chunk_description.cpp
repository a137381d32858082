// describe_chunk(): the manifest entry of a baked chunk (world/world_manifest.h) from the cloud that
// was written and the header of the file it was written to; describe_records() and widen_bounds(), the
// part that comes from the Gaussians, for the compressed chunk writer too.
#include <algorithm>
#include <fstream>
#include <limits>
#include <span>
#include <vector>

#include "engine/core/error.h"
#include "splat_lod/core/gaussian_extent.h"
#include "splat_lod/core/ply_vertex_layout.h"
#include "splat_lod/core/world_manifest.h"
#include "world/chunk_description.h"

namespace splat_lod::world {
namespace {

// prefix_count[l − 1] = Gaussians with stream level ≥ l; the stream levels must come 4, 3, 2, 1 so
// that each of those sets is a prefix of the file.
std::array<std::uint64_t, kLevels> level_prefixes(const std::vector<std::uint8_t>& stream, const std::string& name) {
    std::array<std::uint64_t, kLevels> counts{};
    int previous = kLevels;
    for (std::size_t i = 0; i < stream.size(); ++i) {
        const int level = stream[i];
        if (level > previous)
            engine::fail(name + ": Gaussian " + std::to_string(i) + " has stream level " + std::to_string(level) +
                         " after stream level " + std::to_string(previous) +
                         ": a chunk must be in stream order (stream level 4 first) so that levels are prefixes");
        previous = level;
        for (int l = 1; l <= level; ++l) ++counts[static_cast<std::size_t>(l - 1)];
    }
    return counts;
}

// Per stream level: the largest extent and the largest extent / coverage_min (−1 when some Gaussian
// has no coverage_min: the level can never be ruled out). Rounded up by a relative 1e−6 so that the
// float bound is never below the double value, as build_clusters() does.
std::array<ChunkLevel, kLevels> level_bounds(const SplatCloud& baked, const std::vector<std::uint8_t>& stream) {
    std::array<ChunkLevel, kLevels> levels{};
    for (std::size_t i = 0; i < baked.size(); ++i) {
        ChunkLevel& bound = levels[static_cast<std::size_t>(stream[i] - 1)];
        const double extent = gaussian_extent(baked.log_scales[i], baked.opacity_logits[i]);
        bound.extent_max = std::max(bound.extent_max, static_cast<float>(extent * (1.0 + 1e-6)));
        const float coverage_min = baked.coverage_min.empty() ? -1.0f : baked.coverage_min[i];
        if (!(coverage_min > 0.0f) || bound.extent_per_min_coverage_max < 0.0f)
            bound.extent_per_min_coverage_max = -1.0f;
        else
            bound.extent_per_min_coverage_max =
                std::max(bound.extent_per_min_coverage_max, static_cast<float>(extent / coverage_min * (1.0 + 1e-6)));
    }
    return levels;
}

// The header's and every record block's CRC-32 (world_manifest.h: checksums), from the bytes on disk.
void checksum_file(const std::filesystem::path& path, const io::PlyVertexLayout& layout, ChunkEntry& entry) {
    std::ifstream in(path, std::ios::binary);
    if (!in) engine::fail(path.string() + ": cannot open to compute its checksums");
    std::vector<std::uint8_t> bytes(
        static_cast<std::size_t>(std::max(layout.header_bytes, kChecksumBlockRecords * layout.vertex_bytes)));
    const auto read = [&](std::uint64_t size) {
        in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
        if (static_cast<std::uint64_t>(in.gcount()) != size)
            engine::fail(path.string() + ": ended while its checksums were computed (changed while being described)");
        return checksum(std::span(bytes.data(), static_cast<std::size_t>(size)));
    };
    entry.header_crc32 = read(layout.header_bytes);
    entry.record_crc32.clear();
    for (const RecordBlock& block : record_blocks(entry, 0, entry.prefix_count[0]))
        entry.record_crc32.push_back(read((block.end - block.begin) * layout.vertex_bytes));
}

}  // namespace

ChunkEntry describe_records(const SplatCloud& baked, const std::filesystem::path& file, const glm::ivec2& cell,
                            const StreamLevelRule& rule, const std::string& name, std::vector<std::uint8_t>& stream) {
    baked.check_consistent();
    ChunkEntry entry;
    entry.id = chunk_id(cell);
    entry.file = file;
    entry.cell = cell;
    for (const std::uint8_t level : baked.lod_level)
        if (level < 1 || level > kLevels)
            engine::fail(name + ": a Gaussian has bake level " + std::to_string(level) + ", expected 1..4");
    stream = stream_levels(baked, rule);
    entry.prefix_count = level_prefixes(stream, name);
    entry.levels = level_bounds(baked, stream);
    if (!baked.empty()) {
        entry.bounds_min = glm::vec3(std::numeric_limits<float>::max());
        entry.bounds_max = glm::vec3(std::numeric_limits<float>::lowest());
    }
    widen_bounds(entry, baked, stream);
    return entry;
}

void widen_bounds(ChunkEntry& entry, const SplatCloud& stored, const std::vector<std::uint8_t>& stream) {
    const std::array<ChunkLevel, kLevels> levels = level_bounds(stored, stream);
    for (std::size_t l = 0; l < kLevels; ++l) {
        ChunkLevel& bound = entry.levels[l];
        bound.extent_max = std::max(bound.extent_max, levels[l].extent_max);
        const bool always = bound.extent_per_min_coverage_max < 0.0f || levels[l].extent_per_min_coverage_max < 0.0f;
        bound.extent_per_min_coverage_max =
            always ? -1.0f : std::max(bound.extent_per_min_coverage_max, levels[l].extent_per_min_coverage_max);
    }
    for (const glm::vec3& p : stored.positions) {
        entry.bounds_min = glm::min(entry.bounds_min, p);
        entry.bounds_max = glm::max(entry.bounds_max, p);
    }
}

ChunkEntry describe_chunk(const SplatCloud& baked, const std::filesystem::path& folder,
                          const std::filesystem::path& file, const glm::ivec2& cell, const StreamLevelRule& rule) {
    const std::filesystem::path path = folder / file;
    const std::string name = path.string();
    std::vector<std::uint8_t> stream;
    ChunkEntry entry = describe_records(baked, file, cell, rule, name, stream);
    const io::PlyVertexLayout layout = io::read_ply_vertex_layout(path);
    if (layout.vertex_count != baked.size() ||
        layout.file_bytes != layout.header_bytes + layout.vertex_count * layout.vertex_bytes)
        engine::fail(name + ": holds " + std::to_string(layout.vertex_count) + " records in " +
                     std::to_string(layout.file_bytes) + " bytes, expected the " + std::to_string(baked.size()) +
                     " Gaussians of the cloud that was written");
    entry.header_bytes = layout.header_bytes;
    entry.vertex_bytes = layout.vertex_bytes;
    entry.file_bytes = layout.file_bytes;
    checksum_file(path, layout, entry);
    return entry;
}

}  // namespace splat_lod::world
