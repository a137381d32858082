#pragma once
// The sample world: generated from a seed, split into a grid of chunks, each chunk baked into a
// LOD asset (coarse levels first) and described in a manifest (world_manifest.h), written into a
// folder that later runs reuse as a cache:
//   <output>/world.json                            the manifest, written last (its presence = complete)
//   <output>/gen-<n>/chunks/chunk_+003_-002.lod.ply  one baked chunk per grid cell
//   <output>/gen-<n>/meshes/{house,fence,post,terrain}.glb   the props and the ground mesh
//   <output>/gen-<n>/groups/group_2_+001_+000.lod.ply  the chunk groups (world_groups.h), pooled from the
//                                                    chunks once they are all written
// A cached world whose chunks match but whose groups were made with other settings (or that has none,
// like worlds made before groups) gets new groups only: they go into a new gen-<n>/, and the new
// manifest names the chunks and meshes where they already are.
// The manifest names its files by paths relative to <output>, so readers need not know the layout.
//
// Output safety: users never lose a world they had. world.json is the single commit point: a run
// writes all its files into a new generation folder gen-<n> (n one above every gen-<n> present; a
// fresh folder gets gen-1), which no manifest names, each file synced to disk before its rename
// into place; then it replaces world.json atomically (temporary file, fsync, rename, fsync of the
// folder); only after that does it remove what the new manifest does not name (the previous
// generation, folders of killed runs, and chunks/ and meshes/ files of worlds made before
// generation folders; nothing else in <output>). A run killed or failing at any moment therefore
// leaves the previous world.json and every file it names untouched, or the new world complete; a
// failed run removes its own generation folder, a killed run's is removed by the next run (a cached
// one too). One run at a time per folder, and none while a program streams the world: a run holds
// an exclusive flock() on <output> while it writes or removes files there (world_lock.h; released by
// the kernel if it dies), a streaming program a shared one, and a run that cannot take the lock
// fails saying who holds it (a cached world is still returned without it, and nothing is removed).
// Worlds in the flat layout (chunks/, meshes/) read as before. A bake may also be split into shards
// run as separate processes and merged into the same bytes (world_shards.h); their files wait in a
// staging folder, staging-<hash>/, until the merge renames it to the next gen-<n> and commits.
//
// Content (world_terrain.h for the ground): hills with a river valley winding along z and a path
// winding along x; ground Gaussians over all of it (meadow, forest floor, the path's dirt, banks),
// bluish flat water Gaussians on the river, forests and lone trees of cm-sized leaves, grass patches
// of thin blades, rocks, and houses along the path with picket-fenced gardens (Gaussians), fence runs
// and waymark posts (glTF props). No tree, rock or grass stands on the path, in the river or inside a
// prop. The default world is 1024 m, 256 chunks of 64 m, density 1, seed 1; its size and what it
// costs to make are in docs/world_lod.md ("The chunk bake").
//
// Determinism: the files depend only on the options (seed, sizes, density, bake settings), not on
// the thread count or the order chunks finish in: every object draws from its own random stream,
// each chunk is baked single-threaded (bake_lod is deterministic anyway) and the manifest lists
// chunks in grid order. The generation number n is the one thing that depends on what the folder
// held: it is part of the manifest's paths, never of a chunk's or mesh's bytes (a fresh folder:
// gen-1, so the same options give the same folder byte for byte).
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "splat_lod/bake/bake.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/worldgen/world_groups.h"

namespace splat_lod::world {

struct WorldProgress {
    // "meshes", "chunks", "manifest", "clean-up" (after the commit), "cached"; a shard's "shard record",
    // a merge's "merge" (the check of the shards' records)
    std::string stage;
    std::size_t chunks_done = 0;
    std::size_t chunks_total = 0;
    std::uint64_t gaussians = 0;   // in the chunks baked so far
    double elapsed_seconds = 0.0;  // since generate_world() started
    double eta_seconds = -1.0;     // for the remaining chunks; −1 before the first is done
};

// The bake recipe of every chunk: one recipe (adaptive cells, enlargement ≤ 8; choose_recipe off
// halves the bake time), a short refinement (60 iterations per coarse level on 8 of the chunk's 24
// cameras), single-threaded. Coverage ranges take S_min at the 75th percentile instead of the 10th
// (docs/algorithms.md §4 step 6): most chunk views see a leaf from far away or edge-on, so the 10th
// percentile is tiny and the "not too small" test (S / S_min ≥ S_rel_min) then keeps every leaf
// selectable from any distance. The measurements behind both choices are in docs/world_lod.md ("The
// chunk bake").
bake::BakeOptions default_world_bake_options();

// The most chunks a world has along a side (validate() refuses more; an import sizes its chunks to fit).
inline constexpr int kMaxChunksPerSide = 1024;

struct WorldOptions {
    std::uint64_t seed = 1;
    float size_m = 1024.0f;      // the world spans [−size/2, size/2] in x and z
    float chunk_size_m = 64.0f;  // size_m must be a whole multiple of it
    float density = 1.0f;        // scales every Gaussian count, (0, 8]
    int threads = 0;             // chunks baked at once (each bake single-threaded); 0: all cores
    bake::BakeOptions bake = default_world_bake_options();
    int bake_width = 512;  // chunk camera images: both sides divisible by 64 for the refinement
    int bake_height = 384;
    bool terrain_mesh = true;  // write meshes/terrain.glb and name it in the manifest
    // Smallest reach (metres per pixel of focal length) of stream levels 4, 3, 2 (stream_levels.h);
    // the reaches are computed with the bake's S_T and S_rel_min.
    std::array<float, 3> stream_reach_min = StreamLevelRule{}.reach_min;
    GroupOptions groups;  // the chunk groups pooled from the chunks (world_groups.h)
    // How chunk and group files store their Gaussians (world_manifest.h): compressed compact records
    // (about 15.7 bytes a Gaussian at SH 0, quantised as the GPU's compact storage quantises) or the
    // lossless PLY files of manifest version 4 (77 bytes at SH 0).
    ChunkCodec chunk_codec = ChunkCodec::compact;
    std::filesystem::path output;  // the world's folder (created)
    bool force = false;            // regenerate even when the cached world matches
    std::function<void(const WorldProgress&)> progress;
};

// Throws engine::Error naming the first bad option.
void validate(const WorldOptions& options);

// The manifest's `generator` string for these options: the content version and every bake setting.
std::string generator_settings(const WorldOptions& options);

// How the chunk files of these options are split into stream levels: the bake's S_T and S_rel_min
// with stream_reach_min.
StreamLevelRule stream_level_rule(const WorldOptions& options);

// The world already in options.output when its manifest reads back, matches the options (version,
// seed, size, chunk size, density, generator settings) and every chunk and mesh file it names exists
// with its recorded size; otherwise nullopt and, in `why_not`, the reason. Its chunk groups may still
// be stale (groups_current()).
std::optional<WorldManifest> find_cached_world(const WorldOptions& options, std::string* why_not = nullptr);
// True when the manifest's groups are those of the options (group_generator_settings) and every group
// file exists with its recorded size; otherwise false and, in `why_not`, the reason. A cached world
// whose groups are stale gets new groups only (its chunks are kept where they are).
bool groups_current(const WorldManifest& manifest, const WorldOptions& options, std::string* why_not = nullptr);

struct StageSeconds {
    std::string stage;
    double seconds = 0.0;
};

struct WorldSummary {
    bool cached = false;
    std::string cache_note;  // why the cache was not used (when it was not)
    std::size_t chunks = 0;
    std::size_t props = 0;
    std::uint64_t fine_gaussians = 0;                          // level 1: what the generator made (0 when cached)
    std::array<std::uint64_t, kLevels> gaussians_per_level{};  // on disk by bake level, [l − 1] (0 when cached)
    std::array<std::uint64_t, kLevels> gaussians_per_stream_level{};  // on disk by stream level, [l − 1]
    std::uint64_t gaussians = 0;                                      // on disk, all levels
    std::uint64_t chunk_bytes = 0, mesh_bytes = 0;
    std::size_t groups = 0;  // chunk groups (world_groups.h) and their Gaussians and bytes
    std::uint64_t group_gaussians = 0, group_bytes = 0;
    bool groups_rebuilt = false;  // a cached world's chunks with new groups
    // Generated (level-1) Gaussians by kind; trees are counted as objects (empty for a cached world).
    std::uint64_t ground = 0, water = 0, trees = 0, tree_gaussians = 0, grass = 0, rocks = 0, fences = 0;
    // The bakes' quality, per level l = 2..4 ([l − 1]; [0] unused): the mean over the chunks of the
    // PSNR (dB) of the finished `full` selection at the level's scale on each chunk's refinement
    // cameras against the area-averaged fine renders, and of the level-1 baseline (unfiltered) on the
    // same views. 0 where no chunk was refined (or for a cached world).
    std::array<double, kLevels> mean_level_psnr{};
    std::array<double, kLevels> mean_baseline_psnr{};
    std::vector<StageSeconds> stages;        // wall-clock: meshes, chunks, manifest
    std::vector<StageSeconds> chunk_stages;  // summed over all chunks (worker seconds): content, bake stages, write
    double seconds = 0.0;
};

struct WorldResult {
    WorldManifest manifest;
    WorldSummary summary;
};

// Generates and bakes the world into options.output, or reuses the cached one there (see
// find_cached_world). A new world is written as described at the top of this file: a new generation
// folder, then world.json (the commit), then the removal of the files it does not name, so an
// interrupted or failed run leaves the previous world intact. Errors throw engine::Error naming the
// chunk or file; another run holding the folder's lock is an error too (unless the cache is used).
WorldResult generate_world(const WorldOptions& options);

// Only the first step: generates every chunk's fine Gaussians (in parallel, nothing written, no
// bake) and returns their counts (fine_gaussians and the counts by kind), for tuning the density.
WorldSummary count_world_content(const WorldOptions& options);

// A multi-line summary: chunks, Gaussians per level and by kind, bytes, stage times.
std::string format_summary(const WorldSummary& summary);

}  // namespace splat_lod::world
