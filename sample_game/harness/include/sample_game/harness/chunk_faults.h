#pragma once
// Damages the chunk files of a world while it streams, for the soak run (soak_run.h): a chunk file
// disappears, is cut short, is replaced by another chunk's file, or has bits flipped at the same
// size, and later comes back. It works on a linked copy of the world (make_linked_world_copy),
// never on the user's own files: every change replaces a directory entry by rename, so the
// hard-linked originals are never written.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "splat_lod/core/world_manifest.h"

namespace sample_game {

enum class FaultKind { removed, truncated, replaced, corrupted };
std::string_view to_string(FaultKind kind);

// Makes `copy` a world that reads like `world`: world.json copied, every other file hard-linked
// (copied where the file system cannot link). Whatever `copy` held before is removed first. Throws
// engine::Error when `copy` is `world` itself or lies inside it, or on an I/O error.
void make_linked_world_copy(const std::filesystem::path& world, const std::filesystem::path& copy);

struct ChunkFault {
    std::size_t chunk = 0;  // index in the manifest
    std::string chunk_id;
    FaultKind kind = FaultKind::removed;
};

class ChunkFaults {
public:
    ChunkFaults(std::filesystem::path folder, const splat_lod::world::WorldManifest& manifest);
    ~ChunkFaults();  // restores what is still damaged
    ChunkFaults(const ChunkFaults&) = delete;
    ChunkFaults& operator=(const ChunkFaults&) = delete;

    // removed: the file is gone; truncated: it holds the first 60 % of its bytes; replaced: it holds
    // the bytes of chunk `donor`'s file; corrupted: its own bytes with the lowest bit of the first
    // byte of every checksum block's first record flipped (world_manifest.h: the same size and
    // header, every value finite, a position moved by one float step: only the checksums show it).
    // The original is set aside until restore_all().
    void apply(std::size_t chunk, FaultKind kind, std::size_t donor = 0);
    // Puts every original back (an atomic rename over the damaged file).
    void restore_all();
    const std::vector<ChunkFault>& active() const { return active_; }
    // The fault on this chunk id, if any is active.
    const ChunkFault* find(std::string_view chunk_id) const;

private:
    std::filesystem::path file(std::size_t chunk) const;

    std::filesystem::path folder_;
    const splat_lod::world::WorldManifest& manifest_;
    std::vector<ChunkFault> active_;
};

}  // namespace sample_game
