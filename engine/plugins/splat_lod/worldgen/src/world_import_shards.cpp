// Sharded imports (world_import.h): each shard reads the whole capture, bins and bakes only its own chunks
// into the staging folder and writes its record; the merge checks the records against the files, pools the
// chunk groups there, renames the staged generation and commits world.json as a whole import does.
#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <system_error>

#include <unistd.h>

#include "engine/core/error.h"
#include "engine/core/process_memory.h"
#include "shard_staging.h"
#include "splat_lod/core/world_lock.h"
#include "splat_lod/worldgen/world_import.h"
#include "world_folder.h"
#include "world_import_steps.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;

fs::path import_staging(const ImportOptions& o, const ImportPlan& plan) {
    return o.output / ("staging-import-" + plan.fingerprint);
}

bool shard_owns(const CaptureFrame& frame, const glm::ivec2& cell, const WorldShard& shard) {
    return cell_index(frame, cell) % shard.count == shard.index - 1;
}

// A shard's record, checked: made by this import (same generator), its chunks the shard's and where
// shards write them, each file matching its entry; the far layer (shard 1's) present.
WorldManifest read_import_record(const fs::path& staging, const WorldShard& shard, const CaptureFrame& frame,
                                 const std::string& generator) {
    const fs::path path = staging / shard_record_name(shard);
    WorldManifest record = read_world_manifest(path);
    if (record.generator != generator) engine::fail(path.string() + ": made by another import than this one");
    for (const ChunkEntry& c : record.chunks) {
        if (!shard_owns(frame, c.cell, shard) || c.id != chunk_id(c.cell) ||
            c.file != chunk_file(kStagedGeneration, c.cell, c.codec))
            engine::fail(path.string() + ": chunk " + c.id + " is not one of the shard's or not where shards write it");
        check_chunk_file(staging / c.file, c);
    }
    std::error_code ec;
    for (const Prop& p : record.props)
        if (!fs::is_regular_file(staging / p.mesh, ec))
            engine::fail(path.string() + ": its far layer " + (staging / p.mesh).string() + " is missing");
    return record;
}

// The shards' records, all of one count N and all N of them, or an error naming what is missing.
std::vector<WorldShard> complete_records(const ImportOptions& o, const fs::path& staging) {
    std::map<std::size_t, std::set<std::size_t>> done;  // N → the I with a record
    for (const WorldShard& shard : shard_records(staging)) done[shard.count].insert(shard.index);
    if (done.empty())
        engine::fail(o.output.string() + ": cannot merge: no shard has finished (no " +
                     (staging / "shard-<I>-of-<N>.json").string() + "); nothing was written");
    if (done.size() > 1)
        engine::fail(staging.string() + ": records of shards of " + std::to_string(done.begin()->first) + " and of " +
                     std::to_string(std::next(done.begin())->first) +
                     " shards: run every shard with one N (remove the others' records), then merge");
    const auto& [count, indices] = *done.begin();
    std::vector<std::string> missing;
    std::vector<WorldShard> shards;
    for (std::size_t index = 1; index <= count; ++index) {
        if (!indices.count(index)) missing.push_back(std::to_string(index) + "/" + std::to_string(count));
        shards.push_back({index, count});
    }
    if (!missing.empty())
        engine::fail(o.output.string() + ": cannot merge: missing shards " + listed(missing, 32) + " (no record in " +
                     staging.string() + "); run them, then merge again (nothing was written)");
    return shards;
}

// The merged manifest from the records, paths still relative to the staging folder: chunks in grid order,
// the far layer of shard 1.
WorldManifest gather_records(const ImportOptions& o, const fs::path& staging, const ImportPlan& plan, WorldManifest m) {
    std::map<std::size_t, ChunkEntry> chunks;  // by grid index
    for (const WorldShard& shard : complete_records(o, staging)) {
        WorldManifest record = read_import_record(staging, shard, plan.frame, m.generator);
        if (shard.index == 1) m.props = record.props;
        for (ChunkEntry& c : record.chunks) chunks.emplace(cell_index(plan.frame, c.cell), std::move(c));
    }
    if (chunks.empty()) engine::fail(o.capture.string() + ": no Gaussian lies inside the world's box");
    for (auto& [index, c] : chunks) {
        m.gaussians += c.prefix_count[0];
        m.chunks.push_back(std::move(c));
    }
    return m;
}

// Removes what the staged generation holds that `m` does not name (temporaries of killed shards).
void prune_unnamed(const fs::path& staging, const WorldManifest& m) {
    std::set<fs::path> keep;
    for (const auto* list : {&m.chunks, &m.groups})
        for (const ChunkEntry& c : *list) keep.insert(c.file);
    for (const Prop& p : m.props) keep.insert(p.mesh);
    prune_staged(staging, keep);
}

// The shard's record when it is there and every file matches it (not with options.force); otherwise
// nothing, with why in the summary's cache note.
std::optional<ImportResult> cached_shard(const ImportOptions& o, const ImportPlan& plan, const fs::path& staging,
                                         const WorldShard& shard, ImportSummary& s, Clock::time_point start) {
    const fs::path record_path = staging / shard_record_name(shard);
    std::error_code ec;
    if (o.force || !fs::exists(record_path, ec)) return std::nullopt;
    try {
        const WorldOptions w = import_world_options(o, plan.frame, 0, staging);
        const auto m = import_manifest(o, w, plan, ground_grid(plan.sample, plan.frame));
        ImportResult cached =
            cached_import_result(read_import_record(staging, shard, plan.frame, m.generator), staging, start);
        cached.record = record_path;
        return cached;
    } catch (const engine::Error& e) {
        s.world.cache_note = e.what();  // baked again
        return std::nullopt;
    }
}

}  // namespace

ImportResult import_world_shard(const ImportOptions& o, const WorldShard& shard) {
    check_shard(shard);
    const auto start = Clock::now();
    ImportSummary s;
    ImportPlan plan = open_import(o, s);
    create_world_folder(o.output);
    if (auto cached = cached_import(o, plan.fingerprint))
        return cached_import_result(std::move(*cached), o.output, start);
    const fs::path staging = import_staging(o, plan);
    std::error_code ec;
    fs::create_directories(staging / kStagedGeneration, ec);
    if (ec) engine::fail(staging.string() + ": cannot create the staging folder: " + ec.message());
    const FolderFlock lock(staging, false);
    if (!lock.held())
        engine::fail(lock.busy() ? staging.string() + ": a merge is using this staging folder; wait for it"
                                 : lock.problem());
    s.run = "shard " + std::to_string(shard.index) + "/" + std::to_string(shard.count);
    survey_import(o, plan, s, start);
    const fs::path record_path = staging / shard_record_name(shard);
    if (auto cached = cached_shard(o, plan, staging, shard, s, start)) return std::move(*cached);

    // Each run its own bins (a requeued shard may run while its first run still does).
    const std::string bins_folder =
        "bins-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + "-" + std::to_string(::getpid());
    ImportResult result;
    WorldManifest& record = result.manifest;
    WorldOptions w;
    // Every shard computes the far layer the same way; one writes it.
    record = bake_capture(
        o, plan, staging, kStagedGeneration, staging / bins_folder,
        [&](const glm::ivec2& cell) { return shard_owns(plan.frame, cell, shard); }, shard.index == 1, w, s, start);
    write_world_manifest(record_path, record);
    result.record = record_path;
    summarise_manifest(record, staging, s.world);
    s.world.seconds = seconds_since(start);
    s.peak_rss_bytes = engine::process_memory().peak_resident_bytes;
    result.summary = std::move(s);
    return result;
}

ImportResult merge_import_shards(const ImportOptions& o) {
    const auto start = Clock::now();
    ImportSummary s;
    ImportPlan plan = open_import(o, s);
    std::error_code ec;
    if (!fs::is_directory(o.output, ec)) engine::fail(o.output.string() + ": cannot merge: no such folder");
    const WorldFolderLock lock(o.output, WorldFolderLock::Mode::write);
    if (auto cached = cached_import(o, plan.fingerprint))
        return cached_import_result(std::move(*cached), o.output, start);
    lock.require();
    const fs::path staging = import_staging(o, plan);
    std::optional<FolderFlock> staging_lock;
    lock_staging(o.output, staging, staging_lock);
    s.run = "merged world";
    survey_import(o, plan, s, start);

    auto stage = Clock::now();
    const WorldOptions w = import_world_options(o, plan.frame, 0, staging);
    WorldManifest m =
        gather_records(o, staging, plan, import_manifest(o, w, plan, ground_grid(plan.sample, plan.frame)));
    s.world.stages.push_back({"check shards", seconds_since(stage)});
    add_groups(w, kStagedGeneration, m, s.world, start);
    prune_unnamed(staging, m);

    stage = Clock::now();
    const fs::path generation = new_generation(o.output);
    move_to_generation(m, generation);
    commit_staged(o.output, staging, generation, m);
    staging_lock.reset();
    if (const FolderFlock no_shard(staging, true); no_shard.held()) fs::remove_all(staging, ec);
    remove_unnamed_files(o.output, m);
    s.world.stages.push_back({"manifest and clean-up", seconds_since(stage)});
    ImportResult result;
    result.manifest = std::move(m);
    summarise_manifest(result.manifest, o.output, s.world);
    s.world.seconds = seconds_since(start);
    s.peak_rss_bytes = engine::process_memory().peak_resident_bytes;
    result.summary = std::move(s);
    return result;
}

}  // namespace splat_lod::world
