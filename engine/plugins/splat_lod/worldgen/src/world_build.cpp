// The steps of a world bake that unsharded and sharded runs share (world/world_build.h): the chunk
// grid, the chunks baked in parallel (generate, bake, write, describe) and the manifest's other fields.
#include "world_build.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <set>
#include <string>
#include <system_error>
#include <utility>

#include "chunk_cameras.h"
#include "engine/core/error.h"
#include "splat_lod/bake/bake_cameras.h"
#include "splat_lod/core/chunk_writer.h"
#include "splat_lod/core/parallel_for.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/synth/fine_detail_scene.h"
#include "splat_lod/synth/world_streams.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;

// Reports progress after each chunk, with an ETA from the mean time per chunk so far.
class ProgressReporter {
public:
    ProgressReporter(const WorldOptions& o, Clock::time_point start, std::size_t total)
        : options_(o), start_(start), chunks_start_(Clock::now()), total_(total) {}

    void chunk_done(std::uint64_t gaussians) {
        const std::lock_guard lock(mutex_);
        ++done_;
        gaussians_ += gaussians;
        if (!options_.progress) return;
        const double chunk_seconds = seconds_since(chunks_start_);
        WorldProgress p{"chunks",
                        done_,
                        total_,
                        gaussians_,
                        seconds_since(start_),
                        chunk_seconds / static_cast<double>(done_) * static_cast<double>(total_ - done_)};
        options_.progress(p);
    }

private:
    const WorldOptions& options_;
    Clock::time_point start_, chunks_start_;
    std::size_t total_, done_ = 0;
    std::uint64_t gaussians_ = 0;
    std::mutex mutex_;
};

ChunkResult build_chunk(const WorldOptions& o, const ContentContext& context, const fs::path& generation,
                        const ChunkSlot& slot) {
    ContentCounts counts;
    const auto start = Clock::now();
    const SplatCloud fine = make_chunk_content(context, slot.square, &counts);
    const double content_seconds = seconds_since(start);
    const ChunkBake bake{o.bake, o.bake_width, o.bake_height, stream_level_rule(o), o.chunk_codec};
    ChunkResult result = bake_chunk(bake, fine, chunk_camera_poses(*context.terrain, slot.square), o.output,
                                    chunk_file(generation, slot.cell, o.chunk_codec), slot.cell);
    result.counts = counts;
    result.stages.insert(result.stages.begin(), StageSeconds{"content", content_seconds});
    return result;
}

void add_stages(std::vector<StageSeconds>& total, const std::vector<StageSeconds>& more) {
    for (const auto& stage : more) {
        const auto it =
            std::find_if(total.begin(), total.end(), [&](const StageSeconds& s) { return s.stage == stage.stage; });
        if (it == total.end())
            total.push_back(stage);
        else
            it->seconds += stage.seconds;
    }
}

// Means over the chunks whose level was refined (the PSNRs are NaN or 0 otherwise).
void average_psnr(const std::vector<ChunkResult>& chunks, WorldSummary& s) {
    std::array<double, kLevels> count{};
    for (const auto& chunk : chunks)
        for (const auto& level : chunk.levels) {
            if (level.refine_iterations == 0 || !std::isfinite(level.final_psnr) ||
                !std::isfinite(level.refine_psnr_baseline))
                continue;
            const auto l = static_cast<std::size_t>(level.level - 1);
            s.mean_level_psnr[l] += level.final_psnr;
            s.mean_baseline_psnr[l] += level.refine_psnr_baseline;
            count[l] += 1.0;
        }
    for (std::size_t l = 0; l < kLevels; ++l)
        if (count[l] > 0.0) {
            s.mean_level_psnr[l] /= count[l];
            s.mean_baseline_psnr[l] /= count[l];
        }
}

}  // namespace

ChunkResult bake_chunk(const ChunkBake& how, const SplatCloud& fine, const std::vector<eval::CameraPose>& poses,
                       const fs::path& output, const fs::path& file, const glm::ivec2& cell) {
    ChunkResult result;
    const auto cameras = bake::bake_cameras(poses, how.width, how.height);
    bake::BakeOptions bake_options = how.options;
    bake_options.threads = 1;  // the chunks are the parallelism
    bake_options.progress = nullptr;
    bake::BakeSummary summary;
    const SplatCloud baked = bake::bake_lod(fine, cameras, bake_options, &summary);
    for (const auto& stage : summary.stages) result.stages.push_back({"bake: " + stage.stage, stage.seconds});
    result.levels = summary.levels;

    write_chunk(how, baked, output, file, cell, result);
    return result;
}

void write_chunk(const ChunkBake& how, const SplatCloud& baked, const fs::path& output, const fs::path& file,
                 const glm::ivec2& cell, ChunkResult& result) {
    const auto start = Clock::now();
    const SplatCloud ordered = baked.permuted(stream_order(baked, how.rule));
    for (const std::uint8_t level : ordered.lod_level) ++result.bake_level_counts[static_cast<std::size_t>(level - 1)];
    result.entry = write_chunk_file(ordered, output, file, cell, how.rule, how.codec);
    result.stages.push_back({"write", seconds_since(start)});
}

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<ChunkSlot> chunk_slots(const WorldOptions& o) {
    const int count = static_cast<int>(std::round(o.size_m / o.chunk_size_m));
    std::vector<ChunkSlot> slots;
    for (int j = 0; j < count; ++j)
        for (int i = 0; i < count; ++i) {
            ChunkSlot slot;
            slot.cell = {i - count / 2, j - count / 2};
            slot.square.lo =
                glm::vec2(-0.5f * o.size_m) + o.chunk_size_m * glm::vec2(static_cast<float>(i), static_cast<float>(j));
            slot.square.hi = slot.square.lo + glm::vec2(o.chunk_size_m);
            slots.push_back(slot);
        }
    return slots;
}

fs::path chunk_file(const fs::path& generation, const glm::ivec2& cell, ChunkCodec codec) {
    return generation / "chunks" / (chunk_id(cell) + chunk_extension(codec));
}

ContentContext content_context(const WorldOptions& o, const WorldTerrain& terrain, const WorldLayout& layout) {
    ContentContext context;
    context.seed = o.seed;
    context.density = o.density;
    context.terrain = &terrain;
    context.layout = &layout;
    context.colour_seed = synth::Rng(o.seed, stream_id(StreamKind::terrain, 1, 0)).next_u64();
    return context;
}

std::vector<ChunkResult> build_chunks(const WorldOptions& o, const ContentContext& context, const fs::path& generation,
                                      const std::vector<ChunkSlot>& slots, Clock::time_point start) {
    std::vector<ChunkResult> results(slots.size());
    ProgressReporter progress(o, start, slots.size());
    if (o.progress) o.progress({"chunks", 0, slots.size(), 0, seconds_since(start), -1.0});
    reference::detail::parallel_for(slots.size(), reference::detail::resolve_thread_count(o.threads),
                                    [&](std::size_t k) {
                                        try {
                                            results[k] = build_chunk(o, context, generation, slots[k]);
                                        } catch (const std::exception& e) {
                                            engine::fail(chunk_id(slots[k].cell) + ": " + e.what());
                                        }
                                        progress.chunk_done(results[k].entry.prefix_count[0]);
                                    });
    return results;
}

WorldManifest manifest_without_chunks(const WorldOptions& o, const WorldLayout& layout, const fs::path& generation) {
    WorldManifest m;
    m.seed = o.seed;
    m.size_m = o.size_m;
    m.chunk_size_m = o.chunk_size_m;
    m.feature_m = WorldTerrain::feature_scale_for(o.size_m);
    m.density = o.density;
    m.generator = generator_settings(o);
    m.stream_levels = stream_level_rule(o);
    m.props = layout.props;
    for (Prop& p : m.props) p.mesh = generation / p.mesh;
    if (o.terrain_mesh) m.terrain_mesh = generation / kTerrainMesh;
    return m;
}

void add_chunk_results(std::vector<ChunkResult>& chunks, WorldManifest& m, WorldSummary& s) {
    average_psnr(chunks, s);
    ContentCounts counts;
    for (auto& chunk : chunks) {
        m.gaussians += chunk.entry.prefix_count[0];
        m.chunks.push_back(std::move(chunk.entry));
        counts += chunk.counts;
        add_stages(s.chunk_stages, chunk.stages);
        for (std::size_t l = 0; l < kLevels; ++l) s.gaussians_per_level[l] += chunk.bake_level_counts[l];
    }
    fill_counts(counts, s);
}

void add_groups(const WorldOptions& o, const fs::path& generation, WorldManifest& m, WorldSummary& s,
                Clock::time_point start) {
    m.groups.clear();
    m.group_generator = group_generator_settings(o.groups);
    if (!o.groups.enabled) return;
    const auto stage_start = Clock::now();
    const auto progress = [&](const GroupProgress& p) {
        if (o.progress) o.progress({"groups", p.done, p.total, 0, seconds_since(start), -1.0});
    };
    m.groups = build_groups(o.output, generation, m.chunks, o.size_m, o.chunk_size_m, o.groups, stream_level_rule(o),
                            o.chunk_codec, o.threads, progress);
    s.stages.push_back({"chunk groups", seconds_since(stage_start)});
}

void fill_counts(const ContentCounts& counts, WorldSummary& s) {
    s.ground = counts.ground;
    s.water = counts.water;
    s.trees = counts.trees;
    s.tree_gaussians = counts.tree_gaussians;
    s.grass = counts.grass;
    s.rocks = counts.rocks;
    s.fences = counts.fences;
}

void summarise_manifest(const WorldManifest& m, const fs::path& folder, WorldSummary& s) {
    s.chunks = m.chunks.size();
    s.props = m.props.size();
    s.gaussians = m.gaussians;
    for (const auto& c : m.chunks) {
        for (int l = 1; l <= kLevels; ++l) {
            const std::uint64_t next = l == kLevels ? 0 : c.prefix_count[static_cast<std::size_t>(l)];
            s.gaussians_per_stream_level[static_cast<std::size_t>(l - 1)] +=
                c.prefix_count[static_cast<std::size_t>(l - 1)] - next;
        }
        s.chunk_bytes += c.file_bytes;
    }
    s.groups = m.groups.size();
    s.group_gaussians = 0;
    s.group_bytes = 0;
    for (const auto& g : m.groups) {
        s.group_gaussians += g.prefix_count[0];
        s.group_bytes += g.file_bytes;
    }
    std::set<fs::path> meshes;
    for (const auto& p : m.props) meshes.insert(p.mesh);
    if (!m.terrain_mesh.empty()) meshes.insert(m.terrain_mesh);
    std::error_code ec;
    for (const auto& mesh : meshes) s.mesh_bytes += fs::file_size(folder / mesh, ec);
}

}  // namespace splat_lod::world
