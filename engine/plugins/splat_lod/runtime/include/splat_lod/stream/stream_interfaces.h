#pragma once
// The two ends the chunk streamer (chunk_streamer.h) talks to, kept GL-free: where chunk
// Gaussians come from (a ChunkSource, by default the chunk files) and where resident levels go
// (a ResidencySink, implemented on the GPU by the incremental splat scene; by a recorder in tests).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {

class ChunkSource {
public:
    virtual ~ChunkSource() = default;
    // The Gaussians [begin, end) of a chunk in file order (stream level 4 first), exactly end − begin
    // of them. `file` is the manifest's folder / chunk.file. Throws (any std::exception) with a
    // message saying what is wrong when the file is missing, truncated or corrupt. Called on the
    // streamer's reader thread, one call at a time, so an implementation needs no locking of its own.
    virtual SplatCloud read(const std::filesystem::path& file, const ChunkEntry& chunk, std::uint64_t begin,
                            std::uint64_t end) = 0;
};

// The chunk files themselves, through read_chunk_range() (chunk_reader.h), which checks the file
// against the manifest entry and names the file in its errors.
class FileChunkSource final : public ChunkSource {
public:
    SplatCloud read(const std::filesystem::path& file, const ChunkEntry& chunk, std::uint64_t begin,
                    std::uint64_t end) override;
};

// One upload: a run of consecutive Gaussians of one stream level of one chunk. A level larger than the
// per-frame upload budget arrives as several parts (part 0 .. part_count − 1, in order, possibly
// over several frames); a level is complete with its last part.
struct LevelPart {
    std::string chunk_id;
    int level = 4;           // stream level: 1 (needed only close up) .. 4 (always resident)
    std::uint32_t part = 0;  // index of this part within the level
    std::uint32_t part_count = 1;
    std::uint64_t first = 0;                      // offset of the part's first Gaussian within the level
    std::uint64_t level_gaussians = 0;            // Gaussians in the whole level
    std::shared_ptr<const SplatCloud> gaussians;  // the sink may keep it
    std::uint64_t bytes = 0;                      // gpu_bytes(gaussians->size(), settings.gpu_sh_degree)
    bool visible = true;   // whether the renderer draws it now (the last show() of its chunk or group)
    float opacity = 1.0f;  // the opacity factor to draw it with now (the last fade() of its level, 0 before any)

    bool completes_level() const { return part + 1 == part_count; }
};

class ResidencySink {
public:
    virtual ~ResidencySink() = default;
    // Called on the streamer's thread (the main, GL thread), at most the per-frame budget of bytes
    // per update. Order guarantees: within a chunk, a level's parts arrive only after every coarser
    // level is complete, and in part order. A level may be drawn once complete; drawing a partly
    // uploaded level is allowed but can leave holes where its coarser level is too large to draw.
    // May throw (e.g. out of GPU memory): the streamer then marks the chunk failed.
    virtual void upload(const LevelPart& part) = 0;
    // Frees every uploaded part of that level. Finer levels of the chunk are always released
    // before coarser ones, so what stays resident is always a coarse prefix.
    virtual void release(const std::string& chunk_id, int level) = 0;
    // Draws (or stops drawing) every uploaded part of a chunk or group without freeing it: the
    // streamer keeps a coarse group drawn until the finer chunks that replace it are resident, and the
    // other way round (chunk_streamer.h, "the cut"). Parts uploaded later carry the same state in
    // LevelPart::visible. A sink that draws everything it holds may ignore it.
    virtual void show(const std::string& chunk_id, bool visible) {
        (void)chunk_id;
        (void)visible;
    }
    // The opacity factor in [0, 1] of every uploaded part of one level of a chunk or group
    // (chunk_streamer.h, "fades"): a part that arrives fades in over a few frames, and a node that
    // replaces another fades in while the other fades out. Parts uploaded later carry it in
    // LevelPart::opacity. A sink that cannot fade may ignore it (parts then switch at once).
    virtual void fade(const std::string& chunk_id, int level, float opacity) {
        (void)chunk_id;
        (void)level;
        (void)opacity;
    }
};

}  // namespace splat_lod::world
