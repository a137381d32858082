// generate_world() and the cache check (world/world_generator.h): layout and meshes first, then the
// chunks in parallel (generate, bake, write, describe), all into a new generation folder, then the
// manifest (the commit), then the removal of what it does not name.
#include "splat_lod/world/world_generator.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <string_view>
#include <system_error>
#include <utility>


#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "reference/parallel_for.h"
#include "splat_lod/bake/bake_cameras.h"
#include "splat_lod/splat_io.h"
#include "splat_lod/synth/fine_detail_scene.h"
#include "splat_lod/world/world_lock.h"
#include "world/chunk_cameras.h"
#include "world/chunk_content.h"
#include "world/world_layout.h"
#include "world/world_meshes.h"
#include "world/world_streams.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The chunk grid: `count` × `count` chunks, cell (i − count/2, j − count/2) covering
// [−size/2 + i·chunk, −size/2 + (i + 1)·chunk) in x and likewise in z.
struct ChunkSlot {
    glm::ivec2 cell{0};
    ChunkSquare square;
};

std::vector<ChunkSlot> chunk_slots(const WorldOptions& o) {
    const int count = static_cast<int>(std::round(o.size_m / o.chunk_size_m));
    std::vector<ChunkSlot> slots;
    for (int j = 0; j < count; ++j)
        for (int i = 0; i < count; ++i) {
            ChunkSlot slot;
            slot.cell = {i - count / 2, j - count / 2};
            slot.square.lo = glm::vec2(-0.5f * o.size_m) + o.chunk_size_m * glm::vec2(static_cast<float>(i), static_cast<float>(j));
            slot.square.hi = slot.square.lo + glm::vec2(o.chunk_size_m);
            slots.push_back(slot);
        }
    return slots;
}

fs::path chunk_file(const fs::path& generation, const glm::ivec2& cell) {
    return generation / "chunks" / (chunk_id(cell) + ".lod.ply");
}

// What one worker produced for one chunk.
struct ChunkResult {
    ChunkEntry entry;
    ContentCounts counts;
    std::vector<StageSeconds> stages;
    std::vector<bake::LevelSummary> levels;  // the bake's per-level report
    std::array<std::uint64_t, kLevels> bake_level_counts{};  // Gaussians per bake level, [l − 1]
};

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
        WorldProgress p{"chunks", done_, total_, gaussians_, seconds_since(start_),
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
    ChunkResult result;
    auto start = Clock::now();
    const SplatCloud fine = make_chunk_content(context, slot.square, &result.counts);
    result.stages.push_back({"content", seconds_since(start)});

    const auto poses = chunk_camera_poses(*context.terrain, slot.square);
    const auto cameras = bake::bake_cameras(poses, o.bake_width, o.bake_height);
    bake::BakeOptions bake_options = o.bake;
    bake_options.threads = 1;  // the chunks are the parallelism
    bake_options.progress = nullptr;
    bake::BakeSummary summary;
    const SplatCloud baked = bake::bake_lod(fine, cameras, bake_options, &summary);
    for (const auto& stage : summary.stages) result.stages.push_back({"bake: " + stage.stage, stage.seconds});
    result.levels = summary.levels;

    start = Clock::now();
    const StreamLevelRule rule = stream_level_rule(o);
    const SplatCloud ordered = baked.permuted(stream_order(baked, rule));
    for (const std::uint8_t level : ordered.lod_level) ++result.bake_level_counts[static_cast<std::size_t>(level - 1)];
    const fs::path file = chunk_file(generation, slot.cell);
    write_inria_ply(o.output / file, ordered);
    result.entry = describe_chunk(ordered, o.output, file, slot.cell, rule);
    result.stages.push_back({"write", seconds_since(start)});
    return result;
}

// Output safety. world.json is the world's single commit point. A run writes every file it makes
// into a new generation folder, gen-<n>/ with n one above every gen-<n> already there, so no file
// that the current manifest names is ever replaced or removed; each file is synced to disk before
// it is renamed into place (engine::write_file_atomic). The manifest naming the new files is
// written last, atomically; only then does the run remove what the new manifest does not name: the
// previous generation, leftovers of killed runs and the flat chunks/ and meshes/ files of worlds
// made before generation folders. Killed at any moment, a run leaves either the previous world.json
// with every file it names untouched, or the new one complete (plus files the next run removes).
// Chunk files keep their bytes: only the folder they are in changes with the generation.
constexpr std::string_view kGenerationPrefix = "gen-";

// n of a folder named "gen-<n>" (n >= 1, as std::to_string writes it); 0 for any other name.
std::uint64_t generation_number(const std::string& name) {
    if (name.size() <= kGenerationPrefix.size() || name.compare(0, kGenerationPrefix.size(), kGenerationPrefix) != 0)
        return 0;
    std::uint64_t n = 0;
    const char* const last = name.data() + name.size();
    const auto [end, error] = std::from_chars(name.data() + kGenerationPrefix.size(), last, n);
    if (error != std::errc() || end != last) return 0;
    return name.substr(kGenerationPrefix.size()) == std::to_string(n) ? n : 0;  // "gen-01" is not one of ours
}

// The folder of a new run: one above every generation in `output` (the current one and those of
// killed runs), so a fresh folder always gets gen-1 and the same options the same bytes.
fs::path new_generation(const fs::path& output) {
    std::uint64_t highest = 0;
    std::error_code ec;
    for (fs::directory_iterator it(output, ec), end; !ec && it != end; it.increment(ec))
        highest = std::max(highest, generation_number(it->path().filename().string()));
    if (ec) engine::fail(output.string() + ": cannot list the world's folder: " + ec.message());
    return std::string(kGenerationPrefix) + std::to_string(highest + 1);
}

// The names in `folder`, listed before anything is removed from it (none when it cannot be read).
std::vector<std::string> entry_names(const fs::path& folder) {
    std::vector<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
        names.push_back(it->path().filename().string());
    return names;
}

// A file of the flat layout of worlds made before generation folders: chunks/chunk_*.lod.ply,
// meshes/{house,fence,post,terrain}.glb, or a temporary of one.
bool flat_layout_file(const std::string& folder, const std::string& name) {
    if (folder == "chunks") return name.rfind("chunk_", 0) == 0 && name.find(".lod.ply") != std::string::npos;
    for (const char* mesh : {"house.glb", "fence.glb", "post.glb", "terrain.glb"})
        if (name == mesh || name.rfind(std::string(mesh) + ".tmp-", 0) == 0) return true;
    return false;
}

// Removes what the world generator made in `folder` that `m` does not name: other generation
// folders, flat-layout files (when `m` is not such a world) and manifest temporaries. Nothing else
// in the folder is touched, nor the folder of `m`'s own files. Only
// with the folder's lock held, after `m` was committed. Errors are ignored: a leftover only costs
// space, and the next run tries again.
void remove_unnamed_files(const fs::path& folder, const WorldManifest& m) {
    std::set<fs::path> named;
    for (const auto& c : m.chunks) named.insert(c.file.lexically_normal());
    for (const auto& p : m.props) named.insert(p.mesh.lexically_normal());
    if (!m.terrain_mesh.empty()) named.insert(m.terrain_mesh.lexically_normal());
    std::set<std::string> named_tops;
    for (const auto& path : named) named_tops.insert(path.begin()->string());

    // A world of the flat layout keeps its folders as they are (with meshes it did not place).
    const bool flat_world = named_tops.count("chunks") > 0 || named_tops.count("meshes") > 0;
    const std::string manifest_temporary = std::string(kManifestFileName) + ".tmp-";
    std::error_code ignored;
    for (const std::string& name : entry_names(folder)) {
        const fs::path path = folder / name;
        if (generation_number(name) > 0 && !named_tops.count(name)) {
            fs::remove_all(path, ignored);
        } else if (!flat_world && (name == "chunks" || name == "meshes") && fs::is_directory(path, ignored)) {
            for (const std::string& file : entry_names(path)) {
                if (flat_layout_file(name, file) && !named.count(fs::path(name) / file))
                    fs::remove(path / file, ignored);
            }
            fs::remove(path, ignored);  // only when empty
        } else if (name.rfind(manifest_temporary, 0) == 0) {
            fs::remove(path, ignored);
        }
    }
}

// After a failed manifest write: removes the new generation unless the manifest names it (the
// rename may have happened before the error, e.g. when syncing the folder failed).
void remove_generation_unless_committed(const fs::path& output, const fs::path& generation) {
    std::error_code ec;
    try {
        if (fs::exists(output / kManifestFileName, ec)) {
            const WorldManifest current = read_world_manifest(output / kManifestFileName);
            if (!current.chunks.empty() && *current.chunks.front().file.begin() == generation) return;
        }
    } catch (const engine::Error&) {
        return;  // unreadable: keep the files, the next run removes them if they are not named
    }
    fs::remove_all(output / generation, ec);
}

void add_stages(std::vector<StageSeconds>& total, const std::vector<StageSeconds>& more) {
    for (const auto& stage : more) {
        const auto it = std::find_if(total.begin(), total.end(), [&](const StageSeconds& s) { return s.stage == stage.stage; });
        if (it == total.end()) total.push_back(stage);
        else it->seconds += stage.seconds;
    }
}

// Means over the chunks whose level was refined (the PSNRs are NaN or 0 otherwise).
void average_psnr(const std::vector<ChunkResult>& chunks, WorldSummary& s) {
    std::array<double, kLevels> count{};
    for (const auto& chunk : chunks)
        for (const auto& level : chunk.levels) {
            if (level.refine_iterations == 0 || !std::isfinite(level.final_psnr) || !std::isfinite(level.refine_psnr_baseline))
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

void summarise_manifest(const WorldManifest& m, const fs::path& folder, WorldSummary& s) {
    s.chunks = m.chunks.size();
    s.props = m.props.size();
    s.gaussians = m.gaussians;
    for (const auto& c : m.chunks) {
        for (int l = 1; l <= kLevels; ++l) {
            const std::uint64_t next = l == kLevels ? 0 : c.prefix_count[static_cast<std::size_t>(l)];
            s.gaussians_per_stream_level[static_cast<std::size_t>(l - 1)] += c.prefix_count[static_cast<std::size_t>(l - 1)] - next;
        }
        s.chunk_bytes += c.file_bytes;
    }
    std::set<fs::path> meshes;
    for (const auto& p : m.props) meshes.insert(p.mesh);
    if (!m.terrain_mesh.empty()) meshes.insert(m.terrain_mesh);
    std::error_code ec;
    for (const auto& mesh : meshes) s.mesh_bytes += fs::file_size(folder / mesh, ec);
}

// Layout and meshes, then every chunk over `threads` workers; returns the chunk results in grid order.
std::vector<ChunkResult> build_chunks(const WorldOptions& o, const ContentContext& context, const fs::path& generation,
                                      Clock::time_point start) {
    const std::vector<ChunkSlot> slots = chunk_slots(o);
    std::vector<ChunkResult> results(slots.size());
    ProgressReporter progress(o, start, slots.size());
    if (o.progress) o.progress({"chunks", 0, slots.size(), 0, seconds_since(start), -1.0});
    reference::detail::parallel_for(slots.size(), reference::detail::resolve_thread_count(o.threads), [&](std::size_t k) {
        try {
            results[k] = build_chunk(o, context, generation, slots[k]);
        } catch (const std::exception& e) {
            engine::fail(chunk_id(slots[k].cell) + ": " + e.what());
        }
        progress.chunk_done(results[k].entry.prefix_count[0]);
    });
    return results;
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

void fill_counts(const ContentCounts& counts, WorldSummary& s) {
    s.ground = counts.ground;
    s.water = counts.water;
    s.trees = counts.trees;
    s.tree_gaussians = counts.tree_gaussians;
    s.grass = counts.grass;
    s.rocks = counts.rocks;
    s.fences = counts.fences;
}

}  // namespace

std::optional<WorldManifest> find_cached_world(const WorldOptions& o, std::string* why_not) {
    const auto no = [&](const std::string& why) -> std::optional<WorldManifest> {
        if (why_not) *why_not = why;
        return std::nullopt;
    };
    const fs::path path = o.output / kManifestFileName;
    std::error_code ec;
    if (!fs::exists(path, ec)) return no("no " + path.string());
    WorldManifest m;
    try {
        m = read_world_manifest(path);
    } catch (const engine::Error& e) {
        return no(e.what());
    }
    if (m.seed != o.seed || m.size_m != o.size_m || m.chunk_size_m != o.chunk_size_m || m.density != o.density)
        return no(path.string() + ": made with another seed, size, chunk size or density");
    if (m.generator != generator_settings(o)) return no(path.string() + ": made with other generator or bake settings");
    const auto count = static_cast<std::size_t>(std::round(o.size_m / o.chunk_size_m));
    if (m.chunks.size() != count * count) return no(path.string() + ": does not list every chunk");
    for (const auto& c : m.chunks) {
        const auto size = fs::file_size(o.output / c.file, ec);
        if (ec || size != c.file_bytes) return no((o.output / c.file).string() + ": missing or not the recorded size");
    }
    for (const auto& p : m.props)
        if (!fs::exists(o.output / p.mesh, ec)) return no((o.output / p.mesh).string() + ": missing");
    if (!m.terrain_mesh.empty() && !fs::exists(o.output / m.terrain_mesh, ec))
        return no((o.output / m.terrain_mesh).string() + ": missing");
    return m;
}

WorldSummary count_world_content(const WorldOptions& o) {
    validate(o);
    const auto start = Clock::now();
    const WorldTerrain terrain(o.seed, o.size_m);
    const WorldLayout layout = make_world_layout(terrain, o.seed);
    const ContentContext context = content_context(o, terrain, layout);
    const std::vector<ChunkSlot> slots = chunk_slots(o);
    std::vector<ContentCounts> counts(slots.size());
    std::vector<std::uint64_t> sizes(slots.size());
    reference::detail::parallel_for(slots.size(), reference::detail::resolve_thread_count(o.threads), [&](std::size_t k) {
        sizes[k] = make_chunk_content(context, slots[k].square, &counts[k]).size();
    });
    WorldSummary s;
    s.chunks = slots.size();
    s.props = layout.props.size();
    ContentCounts total;
    for (std::size_t k = 0; k < slots.size(); ++k) {
        total += counts[k];
        s.fine_gaussians += sizes[k];
    }
    fill_counts(total, s);
    s.seconds = seconds_since(start);
    return s;
}

namespace {

// Everything of a new world but the manifest's commit: layout and meshes, then the chunks, all
// below `generation`; returns the manifest that names them.
WorldManifest build_world(const WorldOptions& o, const fs::path& generation, Clock::time_point start, WorldSummary& s) {
    auto stage_start = Clock::now();
    if (o.progress) o.progress({"meshes", 0, 0, 0, seconds_since(start), -1.0});
    const WorldTerrain terrain(o.seed, o.size_m);
    const WorldLayout layout = make_world_layout(terrain, o.seed);
    write_prop_meshes(o.output / generation);
    if (o.terrain_mesh) write_terrain_mesh(o.output / generation, terrain);
    s.stages.push_back({"layout and meshes", seconds_since(stage_start)});

    stage_start = Clock::now();
    std::vector<ChunkResult> chunks = build_chunks(o, content_context(o, terrain, layout), generation, start);
    s.stages.push_back({"chunks (content, bake, write)", seconds_since(stage_start)});

    if (o.progress) o.progress({"manifest", chunks.size(), chunks.size(), 0, seconds_since(start), 0.0});
    WorldManifest m;
    m.seed = o.seed;
    m.size_m = o.size_m;
    m.chunk_size_m = o.chunk_size_m;
    m.density = o.density;
    m.generator = generator_settings(o);
    m.stream_levels = stream_level_rule(o);
    m.props = layout.props;
    for (Prop& p : m.props) p.mesh = generation / p.mesh;
    if (o.terrain_mesh) m.terrain_mesh = generation / kTerrainMesh;
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
    return m;
}

}  // namespace

WorldResult generate_world(const WorldOptions& o) {
    validate(o);
    const auto start = Clock::now();
    WorldResult result;
    WorldSummary& s = result.summary;
    std::error_code ec;
    fs::create_directories(o.output, ec);
    if (ec) engine::fail(o.output.string() + ": cannot create the world's folder: " + ec.message());
    // Held while this run writes or removes files (world_lock.h); a cached world needs no lock.
    const WorldFolderLock lock(o.output, WorldFolderLock::Mode::write);
    if (!o.force) {
        if (auto cached = find_cached_world(o, &s.cache_note)) {
            // What a run killed between its commit and its clean-up left (unless a run is busy here).
            if (lock.held()) remove_unnamed_files(o.output, *cached);
            result.manifest = std::move(*cached);
            s.cached = true;
            summarise_manifest(result.manifest, o.output, s);
            s.seconds = seconds_since(start);
            if (o.progress) o.progress({"cached", s.chunks, s.chunks, s.gaussians, s.seconds, 0.0});
            return result;
        }
    }
    lock.require();

    // Every file goes into a generation folder that no manifest names (see remove_unnamed_files).
    const fs::path generation = new_generation(o.output);
    try {
        result.manifest = build_world(o, generation, start, s);
    } catch (...) {
        fs::remove_all(o.output / generation, ec);
        throw;
    }
    const auto stage_start = Clock::now();
    try {
        write_world_manifest(o.output / kManifestFileName, result.manifest);  // the commit
    } catch (...) {
        remove_generation_unless_committed(o.output, generation);
        throw;
    }
    const std::size_t count = result.manifest.chunks.size();
    if (o.progress) o.progress({"clean-up", count, count, 0, seconds_since(start), 0.0});
    remove_unnamed_files(o.output, result.manifest);
    s.stages.push_back({"manifest and clean-up", seconds_since(stage_start)});

    summarise_manifest(result.manifest, o.output, s);
    s.fine_gaussians = s.gaussians_per_level[0];
    s.seconds = seconds_since(start);
    return result;
}

}  // namespace splat_lod::world
