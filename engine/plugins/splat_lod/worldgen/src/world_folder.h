#pragma once
// Internal to the world generator: the world folder's layout for output safety (world_generator.h):
// generation folders gen-<n>, the staging folder of a sharded bake (world_shards.h), and the
// clean-up after a commit.
#include <cstdint>
#include <filesystem>
#include <string>

#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {

// Creates the world's folder (and its parents) if missing; throws engine::Error naming it otherwise.
void create_world_folder(const std::filesystem::path& output);

// n of a folder named "gen-<n>" (n >= 1, as std::to_string writes it); 0 for any other name.
std::uint64_t generation_number(const std::string& name);

// The folder of a new run: one above every generation in `output` (the current one and those of
// killed runs), so a fresh folder always gets gen-1 and the same options the same bytes.
std::filesystem::path new_generation(const std::filesystem::path& output);

// "staging-<16 hex digits>": the staging folder of a sharded bake of a world with these fields,
// named from a 64-bit FNV-1a hash of them (every field that a chunk's bytes depend on), so that
// shards on any machine agree on it without talking to each other.
std::string staging_folder_name(std::uint64_t seed, float size_m, float chunk_size_m, float density,
                                const std::string& generator);

// Removes what the world generator made in `folder` that `m` does not name: other generation
// folders, flat-layout files (when `m` is not such a world), manifest temporaries and the staging
// folder of `m`'s own options (unless a shard holds its lock). Nothing else in the folder is
// touched: not the folder of `m`'s files, nor the staging folders of other options (shards may be
// baking another world there while this one is served). Only with the folder's lock held, after `m`
// was committed. Errors are ignored: a leftover only costs space, and the next run tries again.
void remove_unnamed_files(const std::filesystem::path& folder, const WorldManifest& m);

// After a failed manifest write: removes the new generation unless the manifest names it (the
// rename may have happened before the error, e.g. when syncing the folder failed).
void remove_generation_unless_committed(const std::filesystem::path& output, const std::filesystem::path& generation);

// A flock() on a folder (the staging folder of a sharded bake), tried once without waiting: shards
// hold it shared while they write there, the merge and the clean-up exclusively. Released by the
// kernel when the process dies.
class FolderFlock {
public:
    FolderFlock(const std::filesystem::path& folder, bool exclusive);
    ~FolderFlock();
    FolderFlock(const FolderFlock&) = delete;
    FolderFlock& operator=(const FolderFlock&) = delete;

    bool held() const { return fd_ >= 0; }
    bool busy() const { return busy_; }  // another process holds it (otherwise problem() says why not)
    const std::string& problem() const { return problem_; }

private:
    int fd_ = -1;
    bool busy_ = false;
    std::string problem_;
};

}  // namespace splat_lod::world
