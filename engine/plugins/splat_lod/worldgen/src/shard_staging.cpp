// What sharded bakes of generated worlds (world_shards.cpp) and sharded imports (world_import_shards.cpp)
// share: record names, the check of a chunk file against its record, the staging lock and the commit.
#include "shard_staging.h"

#include <charconv>
#include <span>
#include <system_error>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_lod/core/chunk_reader.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;

// Whether the world.json in `output` names files in `generation` (unreadable: assumed so, to keep them).
bool manifest_names(const fs::path& output, const fs::path& generation) {
    std::error_code ec;
    if (!fs::exists(output / kManifestFileName, ec)) return false;
    try {
        const WorldManifest current = read_world_manifest(output / kManifestFileName);
        return !current.chunks.empty() && *current.chunks.front().file.begin() == generation;
    } catch (const engine::Error&) {
        return true;
    }
}

}  // namespace

void check_shard(const WorldShard& shard) {
    if (shard.count < 1 || shard.count > kMaxShards || shard.index < 1 || shard.index > shard.count)
        engine::fail("shard " + std::to_string(shard.index) + "/" + std::to_string(shard.count) +
                     ": expected 1 <= I <= N <= " + std::to_string(kMaxShards) + " (I is 1-based)");
}

void prune_staged(const fs::path& staging, const std::set<fs::path>& keep) {
    std::vector<fs::path> remove;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(staging / kStagedGeneration, ec), end; !ec && it != end; it.increment(ec))
        if (!it->is_directory(ec) && !keep.count(it->path().lexically_relative(staging))) remove.push_back(it->path());
    for (const fs::path& path : remove) fs::remove(path, ec);
}

void move_to_generation(WorldManifest& m, const fs::path& generation) {
    for (auto* list : {&m.chunks, &m.groups})
        for (ChunkEntry& c : *list) c.file = generation / c.file.lexically_relative(kStagedGeneration);
    for (Prop& p : m.props) p.mesh = generation / p.mesh.lexically_relative(kStagedGeneration);
}

std::optional<std::size_t> whole_number(const std::string& text) {
    std::size_t n = 0;
    const char* const last = text.data() + text.size();
    const auto [end, error] = std::from_chars(text.data(), last, n);
    if (text.empty() || error != std::errc() || end != last) return std::nullopt;
    return n;
}

// I and N of a record's name "shard-<I>-of-<N>.json"; nullopt for any other name.
std::optional<WorldShard> record_shard(const std::string& name) {
    const std::string prefix = "shard-", middle = "-of-", suffix = ".json";
    if (name.size() <= prefix.size() + middle.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
        return std::nullopt;
    const std::string numbers = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    const std::size_t split = numbers.find(middle);
    if (split == std::string::npos) return std::nullopt;
    const auto index = whole_number(numbers.substr(0, split)),
               count = whole_number(numbers.substr(split + middle.size()));
    if (!index || !count) return std::nullopt;
    const WorldShard shard{*index, *count};
    if (shard.count < 1 || shard.count > kMaxShards || shard.index < 1 || shard.index > shard.count ||
        shard_record_name(shard) != name)
        return std::nullopt;
    return shard;
}

// Throws unless the file holds exactly what the entry records: its size, the header's and every
// record block's checksum (world_manifest.h).
void check_chunk_file(const fs::path& path, const ChunkEntry& entry) {
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (ec) engine::fail(path.string() + ": missing (" + ec.message() + ")");
    if (size != entry.file_bytes)
        engine::fail(path.string() + ": " + std::to_string(size) + " bytes, the shard's record says " +
                     std::to_string(entry.file_bytes));
    const std::vector<std::uint8_t> bytes = engine::read_binary_file(path);
    const std::span<const std::uint8_t> all(bytes);
    if (checksum(all.first(entry.header_bytes)) != entry.header_crc32)
        engine::fail(path.string() + ": the header's checksum is not the one its shard recorded");
    const std::vector<BlockBytes> bytes_of = record_block_bytes(path, entry);
    for (const RecordBlock& block : record_blocks(entry, 0, entry.prefix_count[0])) {
        const BlockBytes& at = bytes_of[block.index];
        if (checksum(all.subspan(at.offset, at.size)) != entry.record_crc32[block.index])
            engine::fail(path.string() + ": byte " + std::to_string(at.offset) + ": records [" +
                         std::to_string(block.begin) + ", " + std::to_string(block.end) +
                         ") do not match the checksum its shard recorded");
    }
}

// The shards' records in the staging folder, by name.
std::vector<WorldShard> shard_records(const fs::path& staging) {
    std::vector<WorldShard> shards;
    std::error_code ec;
    for (fs::directory_iterator it(staging, ec), end; !ec && it != end; it.increment(ec))
        if (const auto shard = record_shard(it->path().filename().string())) shards.push_back(*shard);
    if (ec) engine::fail(staging.string() + ": cannot list the staging folder: " + ec.message());
    return shards;
}

std::string listed(const std::vector<std::string>& items, std::size_t most) {
    std::string text;
    for (std::size_t i = 0; i < items.size() && i < most; ++i) text += (i ? ", " : "") + items[i];
    if (items.size() > most) text += " and " + std::to_string(items.size() - most) + " more";
    return text;
}

// Renames the staged generation to `generation` and commits `m` (naming it); on failure before the
// commit the staged files go back to the staging folder, for another merge.
void commit_staged(const fs::path& output, const fs::path& staging, const fs::path& generation,
                   const WorldManifest& m) {
    std::error_code ec;
    fs::rename(staging / kStagedGeneration, output / generation, ec);
    if (ec)
        engine::fail((staging / kStagedGeneration).string() + ": cannot rename to " + (output / generation).string() +
                     ": " + ec.message());
    try {
        engine::sync_folder(output);
        engine::sync_folder(staging);
        write_world_manifest(output / kManifestFileName, m);  // the commit
    } catch (...) {
        if (!manifest_names(output, generation)) fs::rename(output / generation, staging / kStagedGeneration, ec);
        throw;
    }
}

// Takes the staging folder's lock for the merge, which no shard may hold (a shard still baking).
void lock_staging(const fs::path& output, const fs::path& staging, std::optional<FolderFlock>& staging_lock) {
    std::error_code ec;
    if (!fs::is_directory(staging, ec))
        engine::fail(output.string() + ": cannot merge: no shard of these options has run here (no " +
                     staging.string() + ")");
    staging_lock.emplace(staging, true);
    if (!staging_lock->held())
        engine::fail(staging_lock->busy() ? staging.string() +
                                                ": a shard is still baking into it (it holds the staging "
                                                "folder's lock); wait for every shard to finish, then merge"
                                          : staging_lock->problem());
}

}  // namespace splat_lod::world
