#pragma once
// Writing a world chunk file (world_manifest.h: codecs) and its manifest entry.
#include <filesystem>

#include <glm/vec2.hpp>

#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {

// The file name ending of a chunk file: ".lod.ply" or ".splatc".
inline const char* chunk_extension(ChunkCodec codec) {
    return codec == ChunkCodec::compact ? ".splatc" : ".lod.ply";
}

// Writes `ordered` (in stream_order() of `rule`: stream level 4 first) to folder / file with `codec`,
// through a temporary file and a rename, and returns its manifest entry: describe_chunk() of a PLY file;
// for a compressed one the same fields, its blocks' sizes and checksums read back from the disk, and the
// extent bounds and bounds of the means widened to hold the Gaussians as the file gives them back
// (quantised), which are read back and decoded to make sure they do. Every Gaussian must be drawable for
// `compact` (finite, non-zero rotation). Throws engine::Error naming the file.
ChunkEntry write_chunk_file(const SplatCloud& ordered, const std::filesystem::path& folder,
                            const std::filesystem::path& file, const glm::ivec2& cell, const StreamLevelRule& rule,
                            ChunkCodec codec);

}  // namespace splat_lod::world
