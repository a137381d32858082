#pragma once
// Internal to the chunk files' readers and writers: the parts of a chunk's manifest entry that come from
// its Gaussians, and the compressed reader.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {

// id, file, cell, prefix counts, per-stream-level extent bounds and the bounds of the means of `baked`
// (which must be in stream order; errors name `name`); `stream` receives each Gaussian's stream level.
ChunkEntry describe_records(const SplatCloud& baked, const std::filesystem::path& file, const glm::ivec2& cell,
                            const StreamLevelRule& rule, const std::string& name, std::vector<std::uint8_t>& stream);

// Widens the entry's extent bounds and bounds of the means so that they also hold for `stored`, the
// same Gaussians as a lossy file gives them back (stream levels `stream`, those of the written cloud).
void widen_bounds(ChunkEntry& entry, const SplatCloud& stored, const std::vector<std::uint8_t>& stream);

// read_chunk_range() of a compressed chunk (codec compact), the range and checksum count checked.
SplatCloud read_compact_chunk_range(const std::filesystem::path& file, const ChunkEntry& entry, std::uint64_t begin,
                                    std::uint64_t end);

}  // namespace splat_lod::world
