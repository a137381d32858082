#pragma once
// Sharded world bakes, for batch schedulers (GNU parallel, Slurm job arrays; docs/world_bakes.md):
// `splat_world --shard I/N` bakes shard I of N (I is 1-based, as Slurm's array index and GNU
// parallel's {#} are) into the world's folder, and `splat_world --merge` commits the world once
// every shard is done. The result is byte for byte the world an unsharded run makes
// (world_generator.h): world.json and every file it names, the gen-<n> folder included.
//
// The share: chunk k in grid order (rows of increasing z, each of increasing x) belongs to shard
// (k mod N) + 1. Shards differ in size by at most one chunk, and since neighbouring chunks hold
// similar content (a forest, the river, the houses along the path) dealing them out in turn gives
// every shard a bit of everything, where contiguous ranges would give one shard whole bands of
// forest and another open meadow.
//
// The folder while shards run (<hash>: 16 hex digits of a hash of every option the bytes depend
// on, so that shards agree on it without talking to each other):
//   <output>/staging-<hash>/gen/chunks/*.lod.ply   the shards' chunk files (each written atomically)
//   <output>/staging-<hash>/shard-<I>-of-<N>.json  a shard's record, written atomically when all its
//                                                  chunks are on disk: a world manifest (the same
//                                                  format and checks) listing only its chunks, with
//                                                  their sizes and checksums, paths relative to the
//                                                  staging folder
// A shard touches nothing else: not world.json nor any file it names, so shards may run while a
// game streams the current world, and the folder lock (world_lock.h) is not taken. Instead each
// shard holds a shared flock() on its staging folder, which the merge takes exclusively: a merge
// is refused while a shard on this machine still writes. (Across machines on a network file system
// the records, not the locks, are what the merge trusts: start it after the shards, e.g. as a
// dependent job.) Two runs of one shard at once write the same bytes, each file atomically.
//
// The merge, holding the folder lock like an unsharded run: reads every record, checks every chunk
// file against its record (size, header and block checksums) and that every chunk of the grid is
// there (a missing one is an error naming the missing shards and chunks; nothing is written), writes
// the meshes once into the staging folder's gen/, renames that to the gen-<n> a fresh run would
// take (one above every gen-<n> present: gen-1 in a fresh folder), commits world.json, then removes
// what it does not name, as an unsharded run does (the staging folder with its records among them).
// Steps that need all chunks (coarse levels of chunk groups) belong to the merge, after the check.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "splat_lod/worldgen/world_generator.h"

namespace splat_lod::world {

struct WorldShard {
    std::size_t index = 1;  // 1-based: 1 ≤ index ≤ count
    std::size_t count = 1;
};

inline constexpr std::size_t kMaxShards = 1u << 20;  // the most chunks a world may have

// Parses "I/N" (decimal, 1 ≤ I ≤ N ≤ kMaxShards); throws engine::Error "--shard \"<text>\": <problem>".
WorldShard parse_world_shard(const std::string& text);

// The grid-order indices of the chunks of `shard` among `chunks` chunks: k with k mod N = I − 1.
std::vector<std::size_t> shard_chunk_indices(std::size_t chunks, const WorldShard& shard);

// The staging folder of these options, relative to options.output ("staging-<hash>").
std::filesystem::path staging_folder(const WorldOptions& options);

// "shard-<I>-of-<N>.json", in the staging folder.
std::string shard_record_name(const WorldShard& shard);

// Bakes the shard's chunks into the staging folder and writes its record. Without options.force it
// does nothing when world.json already holds these options' world (summary.cached), and reuses the
// shard's chunks when its record is there and every file matches it (summary.cached, nothing
// written); a record that does not match is rebaked (chunk files atomically replaced, with the same
// bytes when they were right). The summary counts the shard's chunks; its manifest lists them.
WorldResult bake_world_shard(const WorldOptions& options, const WorldShard& shard);

// Commits the world from the shards' records (see above); returns what generate_world() would (the
// per-chunk bake statistics, which only the shards saw, are zero). Without options.force a world
// already committed for these options is returned as cached. Throws engine::Error, leaving
// world.json and the files it names untouched, when a shard is missing, still running or a file
// does not match its record.
WorldResult merge_world_shards(const WorldOptions& options);

}  // namespace splat_lod::world
