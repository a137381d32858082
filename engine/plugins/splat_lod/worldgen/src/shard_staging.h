#pragma once
// Internal to the world generator: what a sharded bake of a generated world (world_shards.h) and a
// sharded import (world_import.h) share: the shards' record names, the check of a chunk file against
// its record, the staging folder's lock for the merge and the commit of the staged generation.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "splat_lod/core/world_manifest.h"
#include "splat_lod/worldgen/world_shards.h"
#include "world_folder.h"

namespace splat_lod::world {

// The staging folder's generation: renamed to gen-<n> by the merge.
inline constexpr const char* kStagedGeneration = "gen";

// A decimal number made of digits only; nullopt for anything else.
std::optional<std::size_t> whole_number(const std::string& text);

// Throws engine::Error unless 1 <= shard.index <= shard.count <= kMaxShards.
void check_shard(const WorldShard& shard);

// I and N of a record's name "shard-<I>-of-<N>.json"; nullopt for any other name.
std::optional<WorldShard> record_shard(const std::string& name);

// The shards' records in the staging folder, by name.
std::vector<WorldShard> shard_records(const std::filesystem::path& staging);

// Throws unless the file holds exactly what the entry records: its size, the header's and every
// record block's checksum (world_manifest.h).
void check_chunk_file(const std::filesystem::path& path, const ChunkEntry& entry);

// "a, b, c and 5 more": at most `most` items.
std::string listed(const std::vector<std::string>& items, std::size_t most = 8);

// Removes every file in the staged generation whose path relative to the staging folder is not in
// `keep`: temporaries of killed shards, anything else put there.
void prune_staged(const std::filesystem::path& staging, const std::set<std::filesystem::path>& keep);

// The paths `m` names in the staged generation (chunks, groups, props) moved to `generation`.
void move_to_generation(WorldManifest& m, const std::filesystem::path& generation);

// Takes the staging folder's lock for the merge, which no shard may hold (a shard still baking);
// throws engine::Error naming the folder when it is missing or busy.
void lock_staging(const std::filesystem::path& output, const std::filesystem::path& staging,
                  std::optional<FolderFlock>& staging_lock);

// Renames the staged generation to `generation` (in `output`) and commits `m` (naming it); on
// failure before the commit the staged files go back to the staging folder, for another merge.
void commit_staged(const std::filesystem::path& output, const std::filesystem::path& staging,
                   const std::filesystem::path& generation, const WorldManifest& m);

}  // namespace splat_lod::world
