// Sharded world bakes (world/world_shards.h): a shard bakes its chunks into the staging folder and
// writes its record; the merge checks the records against the files, writes the meshes, renames the
// staging generation to gen-<n> and commits world.json like an unsharded run (world_generator.cpp).
#include "splat_lod/worldgen/world_shards.h"

#include <charconv>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <system_error>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "shard_staging.h"
#include "splat_lod/core/world_lock.h"
#include "splat_lod/worldgen/world_meshes.h"
#include "world_build.h"
#include "world_folder.h"
#include "world_layout.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;

// The chunk entries of a shard's record (paths relative to the staging folder), each checked: made
// with these options, one of the shard's chunks, named as the shards name them, its file matching.
std::vector<ChunkEntry> read_shard_record(const WorldOptions& o, const fs::path& staging, const WorldShard& shard) {
    const fs::path path = staging / shard_record_name(shard);
    const WorldManifest record = read_world_manifest(path);
    if (record.seed != o.seed || record.size_m != o.size_m || record.chunk_size_m != o.chunk_size_m ||
        record.density != o.density || record.generator != generator_settings(o))
        engine::fail(path.string() + ": made with other options than these");
    const std::vector<ChunkSlot> slots = chunk_slots(o);
    std::set<std::pair<int, int>> cells;
    for (const std::size_t k : shard_chunk_indices(slots.size(), shard))
        cells.insert({slots[k].cell.x, slots[k].cell.y});
    for (const ChunkEntry& c : record.chunks) {
        if (!cells.erase({c.cell.x, c.cell.y}) || c.id != chunk_id(c.cell) ||
            c.file != chunk_file(kStagedGeneration, c.cell, c.codec))
            engine::fail(path.string() + ": chunk " + c.id + " is not one of the shard's or not where shards write it");
        check_chunk_file(staging / c.file, c);
    }
    if (!cells.empty()) engine::fail(path.string() + ": does not list every chunk of the shard");
    return record.chunks;
}

// The error for chunks that no record lists: which chunks, and which shards of every shard count
// seen have no record.
[[noreturn]] void fail_missing(const WorldOptions& o, const fs::path& staging, const std::vector<WorldShard>& records,
                               const std::vector<std::string>& missing_chunks) {
    std::map<std::size_t, std::set<std::size_t>> done;  // N → the I with a record
    for (const WorldShard& shard : records) done[shard.count].insert(shard.index);
    std::vector<std::string> missing_shards;
    for (const auto& [count, indices] : done)
        for (std::size_t index = 1; index <= count; ++index)
            if (!indices.count(index)) missing_shards.push_back(std::to_string(index) + "/" + std::to_string(count));
    const std::string shards =
        records.empty() ? "no shard has finished (no " + (staging / "shard-<I>-of-<N>.json").string() + ")"
                        : "missing shards " + listed(missing_shards, 32) + " (no record in " + staging.string() + ")";
    engine::fail(o.output.string() + ": cannot merge: " + shards + "; " + std::to_string(missing_chunks.size()) +
                 " of " + std::to_string(chunk_slots(o).size()) + " chunks missing: " + listed(missing_chunks) +
                 "; run the missing shards, then merge again (nothing was written)");
}

// Every chunk's entry from the records, in grid order, paths relative to the staging folder.
std::vector<ChunkEntry> gather_chunks(const WorldOptions& o, const fs::path& staging) {
    const std::vector<WorldShard> records = shard_records(staging);
    std::map<std::pair<int, int>, ChunkEntry> entries;
    for (const WorldShard& shard : records)
        for (ChunkEntry& c : read_shard_record(o, staging, shard))
            entries.emplace(std::pair{c.cell.x, c.cell.y}, std::move(c));
    std::vector<ChunkEntry> chunks;
    std::vector<std::string> missing;
    for (const ChunkSlot& slot : chunk_slots(o)) {
        const auto it = entries.find({slot.cell.x, slot.cell.y});
        if (it == entries.end())
            missing.push_back(chunk_id(slot.cell));
        else
            chunks.push_back(std::move(it->second));
    }
    if (!missing.empty()) fail_missing(o, staging, records, missing);
    return chunks;
}

// Removes everything in the staged generation that `m` (paths relative to the staging folder) does
// not name and the meshes are not: temporaries of killed shards, anything else put there.
void prune_staged_generation(const fs::path& staging, const WorldManifest& m) {
    std::set<fs::path> keep;
    for (const ChunkEntry& c : m.chunks) keep.insert(c.file);
    for (const char* mesh : {kHouseMesh, kFenceMesh, kPostMesh, kTerrainMesh})
        keep.insert(fs::path(kStagedGeneration) / mesh);
    prune_staged(staging, keep);
}

WorldResult cached_result(WorldManifest manifest, const fs::path& folder, Clock::time_point start) {
    WorldResult result;
    result.manifest = std::move(manifest);
    result.summary.cached = true;
    summarise_manifest(result.manifest, folder, result.summary);
    result.summary.seconds = seconds_since(start);
    return result;
}

// The meshes go into the staged generation, which then keeps nothing but them and `staged`'s chunks.
void stage_meshes(const WorldOptions& o, const fs::path& staging, const WorldTerrain& terrain,
                  const WorldManifest& staged) {
    write_prop_meshes(staging / kStagedGeneration);
    if (o.terrain_mesh) write_terrain_mesh(staging / kStagedGeneration, terrain);
    prune_staged_generation(staging, staged);
}

// The chunk groups need every chunk: they are pooled here, from the checked chunk files.
std::vector<ChunkEntry> pool_groups(const WorldOptions& o, const fs::path& staging,
                                    const std::vector<ChunkEntry>& chunks, Clock::time_point start) {
    const auto group_progress = [&](const GroupProgress& p) {
        if (o.progress) o.progress({"groups", p.done, p.total, 0, seconds_since(start), -1.0});
    };
    return build_groups(staging, kStagedGeneration, chunks, o.size_m, o.chunk_size_m, o.groups, stream_level_rule(o),
                        o.chunk_codec, o.threads, group_progress);
}

// The world's manifest in `result`, its entries moved from `staged` into a new generation, committed;
// then the staging folder and every file that no manifest names go.
void commit_merge(const WorldOptions& o, const fs::path& staging, const WorldLayout& layout, WorldManifest& staged,
                  std::optional<FolderFlock>& staging_lock, Clock::time_point start, WorldResult& result) {
    const auto stage_start = Clock::now();
    if (o.progress) o.progress({"manifest", staged.chunks.size(), staged.chunks.size(), 0, seconds_since(start), 0.0});
    const fs::path generation = new_generation(o.output);
    WorldManifest& m = result.manifest;
    m = manifest_without_chunks(o, layout, generation);
    move_to_generation(staged, generation);
    for (ChunkEntry& c : staged.chunks) {
        m.gaussians += c.prefix_count[0];
        m.chunks.push_back(std::move(c));
    }
    for (ChunkEntry& g : staged.groups) m.groups.push_back(std::move(g));
    m.group_generator = group_generator_settings(o.groups);
    commit_staged(o.output, staging, generation, m);
    staging_lock.reset();  // the clean-up takes it again to remove the staging folder
    if (o.progress) o.progress({"clean-up", m.chunks.size(), m.chunks.size(), 0, seconds_since(start), 0.0});
    remove_unnamed_files(o.output, m);
    result.summary.stages.push_back({"manifest and clean-up", seconds_since(stage_start)});
}

}  // namespace

WorldShard parse_world_shard(const std::string& text) {
    const auto bad = [&](const std::string& problem) { engine::fail("--shard \"" + text + "\": " + problem); };
    const std::size_t slash = text.find('/');
    const auto index = slash == std::string::npos ? std::nullopt : whole_number(text.substr(0, slash));
    const auto count = slash == std::string::npos ? std::nullopt : whole_number(text.substr(slash + 1));
    if (!index || !count)
        bad("expected I/N: the shard's index I, 1-based, and the number of shards N, e.g. 3/8 (decimal digits only)");
    if (*count < 1 || *count > kMaxShards) bad("the number of shards N must be 1 to " + std::to_string(kMaxShards));
    if (*index < 1 || *index > *count)
        bad("the shard's index is 1-based: 1 <= I <= N (here 1 to " + std::to_string(*count) + ")");
    return {*index, *count};
}

std::vector<std::size_t> shard_chunk_indices(std::size_t chunks, const WorldShard& shard) {
    check_shard(shard);
    std::vector<std::size_t> indices;
    for (std::size_t k = shard.index - 1; k < chunks; k += shard.count) indices.push_back(k);
    return indices;
}

fs::path staging_folder(const WorldOptions& o) {
    return staging_folder_name(o.seed, o.size_m, o.chunk_size_m, o.density, generator_settings(o));
}

std::string shard_record_name(const WorldShard& shard) {
    return "shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".json";
}

WorldResult bake_world_shard(const WorldOptions& o, const WorldShard& shard) {
    validate(o);
    check_shard(shard);
    const auto start = Clock::now();
    if (!o.force)
        if (auto cached = find_cached_world(o)) return cached_result(std::move(*cached), o.output, start);
    std::string cache_note;  // why the shard's own record was not reused
    const fs::path staging = o.output / staging_folder(o);
    std::error_code ec;
    fs::create_directories(staging, ec);
    if (ec) engine::fail(staging.string() + ": cannot create the staging folder: " + ec.message());
    const FolderFlock lock(staging, false);
    if (!lock.held())
        engine::fail(lock.busy()
                         ? staging.string() + ": a merge is using this staging folder (it holds its lock); wait for it"
                         : lock.problem());

    const std::vector<ChunkSlot> all = chunk_slots(o);
    if (!o.force && fs::exists(staging / shard_record_name(shard), ec)) {
        try {
            WorldManifest record = read_world_manifest(staging / shard_record_name(shard));
            record.chunks = read_shard_record(o, staging, shard);  // checks every file
            return cached_result(std::move(record), staging, start);
        } catch (const engine::Error& e) {
            cache_note = e.what();  // baked again
        }
    }

    WorldResult result;
    WorldSummary& s = result.summary;
    s.cache_note = cache_note;
    const WorldTerrain terrain(o.seed, o.size_m, WorldTerrain::feature_scale_for(o.size_m));
    const WorldLayout layout = make_world_layout(terrain, o.seed);
    std::vector<ChunkSlot> slots;
    for (const std::size_t k : shard_chunk_indices(all.size(), shard)) slots.push_back(all[k]);
    auto stage_start = Clock::now();
    const fs::path generation = staging_folder(o) / kStagedGeneration;
    std::vector<ChunkResult> chunks = build_chunks(o, content_context(o, terrain, layout), generation, slots, start);
    s.stages.push_back({"chunks (content, bake, write)", seconds_since(stage_start)});

    stage_start = Clock::now();
    if (o.progress) o.progress({"shard record", chunks.size(), chunks.size(), 0, seconds_since(start), 0.0});
    WorldManifest& record = result.manifest;
    record = manifest_without_chunks(o, layout, kStagedGeneration);
    record.props.clear();  // the merge writes the meshes and names them
    record.terrain_mesh.clear();
    add_chunk_results(chunks, record, s);
    for (ChunkEntry& c : record.chunks) c.file = c.file.lexically_relative(staging_folder(o));
    write_world_manifest(staging / shard_record_name(shard), record);
    s.stages.push_back({"shard record", seconds_since(stage_start)});
    summarise_manifest(record, staging, s);
    s.fine_gaussians = s.gaussians_per_level[0];
    s.seconds = seconds_since(start);
    return result;
}

WorldResult merge_world_shards(const WorldOptions& o) {
    validate(o);
    const auto start = Clock::now();
    std::error_code ec;
    if (!fs::is_directory(o.output, ec)) engine::fail(o.output.string() + ": cannot merge: no such folder");
    const WorldFolderLock lock(o.output, WorldFolderLock::Mode::write);
    std::string cache_note;
    if (!o.force)
        if (auto cached = find_cached_world(o, &cache_note)) {
            if (lock.held()) remove_unnamed_files(o.output, *cached);
            return cached_result(std::move(*cached), o.output, start);
        }
    lock.require();
    const fs::path staging = o.output / staging_folder(o);
    std::optional<FolderFlock> staging_lock;
    lock_staging(o.output, staging, staging_lock);

    WorldResult result;
    WorldSummary& s = result.summary;
    s.cache_note = cache_note;
    if (o.progress) o.progress({"merge", 0, 0, 0, seconds_since(start), -1.0});
    auto stage_start = Clock::now();
    WorldManifest staged;
    staged.chunks = gather_chunks(o, staging);
    s.stages.push_back({"check shards", seconds_since(stage_start)});

    // Everything that needs all chunks goes here, after the check (chunk groups' coarse levels).
    stage_start = Clock::now();
    if (o.progress) o.progress({"meshes", 0, 0, 0, seconds_since(start), -1.0});
    const WorldTerrain terrain(o.seed, o.size_m, WorldTerrain::feature_scale_for(o.size_m));
    const WorldLayout layout = make_world_layout(terrain, o.seed);
    stage_meshes(o, staging, terrain, staged);
    s.stages.push_back({"layout and meshes", seconds_since(stage_start)});

    stage_start = Clock::now();
    staged.groups = pool_groups(o, staging, staged.chunks, start);
    s.stages.push_back({"chunk groups", seconds_since(stage_start)});

    commit_merge(o, staging, layout, staged, staging_lock, start, result);
    summarise_manifest(result.manifest, o.output, s);
    s.seconds = seconds_since(start);
    return result;
}

}  // namespace splat_lod::world
