#pragma once
// Internal to the world generator: the steps that an unsharded run (world_generator.cpp), a shard
// and the merge of a sharded bake (world_shards.cpp) share, so that both make the same bytes: the
// chunk grid, the bake of a list of chunks over a thread pool, and the manifest without its chunks.
#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "chunk_content.h"
#include "splat_lod/bake/bake.h"
#include "splat_lod/core/camera_set.h"
#include "splat_lod/core/chunk_writer.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/worldgen/world_generator.h"
#include "world_layout.h"

namespace splat_lod::world {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start);

// The chunk grid: `count` × `count` chunks, cell (i − count/2, j − count/2) covering
// [−size/2 + i·chunk, −size/2 + (i + 1)·chunk) in x and likewise in z.
struct ChunkSlot {
    glm::ivec2 cell{0};
    ChunkSquare square;
};

// Every chunk of the options in grid order (rows of increasing z, each of increasing x): the order
// the manifest lists them in and the one the shards are dealt from.
std::vector<ChunkSlot> chunk_slots(const WorldOptions& options);

// "<generation>/chunks/chunk_+003_-002.splatc" (".lod.ply" for PLY chunks)
std::filesystem::path chunk_file(const std::filesystem::path& generation, const glm::ivec2& cell, ChunkCodec codec);

// What one worker produced for one chunk.
struct ChunkResult {
    ChunkEntry entry;
    ContentCounts counts;
    std::vector<StageSeconds> stages;
    std::vector<bake::LevelSummary> levels;                  // the bake's per-level report
    std::array<std::uint64_t, kLevels> bake_level_counts{};  // Gaussians per bake level, [l − 1]
    bool unbaked = false;                // an import's chunk that no bake camera sees, written as it is
    bool from_training_cameras = false;  // an import's chunk baked from the capture's own cameras
};

// How a chunk is baked: the recipe, the camera image size, the stream-level rule and codec of its file.
struct ChunkBake {
    bake::BakeOptions options;
    int width = 512, height = 384;
    StreamLevelRule rule;
    ChunkCodec codec = ChunkCodec::compact;
};

// Bakes `fine` (single-threaded) with cameras at `poses`, orders it by stream level, writes it to
// output / file and describes it (entry, per-level counts, stage times from the bake on).
ChunkResult bake_chunk(const ChunkBake& how, const SplatCloud& fine, const std::vector<eval::CameraPose>& poses,
                       const std::filesystem::path& output, const std::filesystem::path& file, const glm::ivec2& cell);

// The tail of bake_chunk: orders `baked` by stream level, writes it to output / file and describes it
// into `result` (entry, per-level counts, the write's time).
void write_chunk(const ChunkBake& how, const SplatCloud& baked, const std::filesystem::path& output,
                 const std::filesystem::path& file, const glm::ivec2& cell, ChunkResult& result);

ContentContext content_context(const WorldOptions& options, const WorldTerrain& terrain, const WorldLayout& layout);

// Generates, bakes and writes `slots` over options.threads workers into options.output / generation
// (each chunk's bytes depend only on the options and its cell); the results in the order of `slots`,
// their entries naming the files relative to options.output. Progress counts `slots` only.
std::vector<ChunkResult> build_chunks(const WorldOptions& options, const ContentContext& context,
                                      const std::filesystem::path& generation, const std::vector<ChunkSlot>& slots,
                                      Clock::time_point start);

// The manifest of these options with no chunks yet: seed, sizes, settings, stream levels, the
// layout's props and the terrain mesh, their meshes in `generation`.
WorldManifest manifest_without_chunks(const WorldOptions& options, const WorldLayout& layout,
                                      const std::filesystem::path& generation);

// Appends the chunks' entries (moved out) to `m` and adds their counts, stages and PSNRs to `s`.
void add_chunk_results(std::vector<ChunkResult>& chunks, WorldManifest& m, WorldSummary& s);

// Builds the chunk groups of m.chunks (files relative to options.output) into `generation` (relative
// to options.output) and sets m.groups and m.group_generator; none when groups are off.
void add_groups(const WorldOptions& options, const std::filesystem::path& generation, WorldManifest& m, WorldSummary& s,
                Clock::time_point start);

void fill_counts(const ContentCounts& counts, WorldSummary& s);

// Chunks, props, Gaussians per stream level and bytes of a manifest's files below `folder`.
void summarise_manifest(const WorldManifest& m, const std::filesystem::path& folder, WorldSummary& s);

}  // namespace splat_lod::world
