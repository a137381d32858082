// The streamed world's manifest, world.json (splat_lod/core/world_manifest.h), through
// parse_world_manifest, the text form of read_world_manifest.
// Contract: a manifest that obeys every rule the header lists (relative paths inside the folder,
// prefix counts that do not grow, byte counts that add up, one checksum per record block) and
// that write_world_manifest writes back to the same values, or engine::Error "<file>: <key path>: <problem>".
#include <cmath>

#include "engine/core/error.h"
#include "splat_fuzz_support.h"
#include "splat_lod/core/world_manifest.h"

namespace {

namespace sw = splat_lod::world;
using splat_fuzz::finite;
using splat_fuzz::require;

void check_relative(const std::filesystem::path& path, bool allow_empty) {
    require(allow_empty || !path.empty(), "paths are not empty");
    require(!path.is_absolute() && !path.has_root_directory(), "paths are relative: " + path.string());
    for (const auto& part : path) require(part != "..", "paths stay in the folder: " + path.string());
}

void check_manifest(const sw::WorldManifest& m) {
    require(m.size_m > 0.0f && m.chunk_size_m > 0.0f && m.chunk_size_m <= m.size_m && std::isfinite(m.size_m),
            "sizes positive and finite");
    require(finite(m.up) && glm::length(m.up) > 0.0f, "up is a finite non-zero vector");
    std::uint64_t total = 0;
    for (const auto& c : m.chunks) {
        check_relative(c.file, false);
        require(finite(c.bounds_min) && finite(c.bounds_max), "chunk bounds finite");
        for (int l = 1; l < sw::kLevels; ++l)
            require(c.prefix_count[static_cast<std::size_t>(l)] <= c.prefix_count[static_cast<std::size_t>(l - 1)],
                    "prefix counts do not grow with the level");
        if (c.codec == sw::ChunkCodec::compact)
            require(c.vertex_bytes == 0 && c.file_bytes >= c.header_bytes, "compressed: no record size, a header");
        else
            require(c.vertex_bytes > 0 && c.prefix_bytes(1) == c.file_bytes,
                    "file_bytes = header + count x vertex bytes");
        require(c.record_crc32.size() == sw::record_block_count(c), "one checksum per record block");
        const auto blocks = sw::record_blocks(c, 0, c.prefix_count[0]);
        require(blocks.size() == c.record_crc32.size(), "the blocks of the whole file are every block");
        for (std::size_t b = 0; b < blocks.size(); ++b)
            require(blocks[b].index == b && blocks[b].begin < blocks[b].end &&
                        blocks[b].end - blocks[b].begin <= c.block_records() &&
                        blocks[b].begin == (b == 0 ? 0 : blocks[b - 1].end),
                    "record blocks are contiguous, in order, and at most block_records() long");
        total += c.prefix_count[0];
    }
    require(total == m.gaussians, "gaussians is the chunks' sum");
    for (const auto& p : m.props) check_relative(p.mesh, false);
    check_relative(m.terrain_mesh, true);
}

void check_round_trip(const sw::WorldManifest& m) {
    const auto path = splat_fuzz::sandbox_dir() / "world.json";
    sw::write_world_manifest(path, m);  // an engine::Error here is a broken promise: not caught
    const sw::WorldManifest r = sw::read_world_manifest(path);
    require(r.seed == m.seed && r.size_m == m.size_m && r.chunk_size_m == m.chunk_size_m && r.up == m.up &&
                r.gaussians == m.gaussians && r.density == m.density && r.generator == m.generator &&
                r.terrain_mesh == m.terrain_mesh && r.chunks.size() == m.chunks.size() &&
                r.props.size() == m.props.size() && r.groups.size() == m.groups.size() &&
                r.group_generator == m.group_generator && r.version == sw::kManifestVersion,
            "the manifest reads back as written");
    for (std::size_t i = 0; i < m.chunks.size(); ++i) {
        const auto &a = m.chunks[i], &b = r.chunks[i];
        require(a.id == b.id && a.file == b.file && a.cell == b.cell && a.prefix_count == b.prefix_count &&
                    a.file_bytes == b.file_bytes && a.header_crc32 == b.header_crc32 &&
                    a.record_crc32 == b.record_crc32 && a.bounds_min == b.bounds_min && a.bounds_max == b.bounds_max,
                "chunk " + std::to_string(i) + " reads back as written");
    }
    for (std::size_t i = 0; i < m.groups.size(); ++i) {
        const auto &a = m.groups[i], &b = r.groups[i];
        require(a.id == b.id && a.file == b.file && a.cell == b.cell && a.depth == b.depth && a.cell_m == b.cell_m &&
                    a.prefix_count == b.prefix_count && a.record_crc32 == b.record_crc32,
                "group " + std::to_string(i) + " reads back as written");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string name = "fuzz/world.json";
    sw::WorldManifest manifest;
    try {
        manifest = sw::parse_world_manifest(splat_fuzz::text_of(data, size), name);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, name);
        return 0;
    }
    check_manifest(manifest);
    check_round_trip(manifest);
    return 0;
}
