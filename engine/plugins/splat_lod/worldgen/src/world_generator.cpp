// generate_world() and the cache check (world/world_generator.h): layout and meshes first, then the
// chunks in parallel (generate, bake, write, describe), all into a new generation folder, then the
// manifest (the commit), then the removal of what it does not name.
#include "splat_lod/worldgen/world_generator.h"

#include <cmath>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "chunk_content.h"
#include "engine/core/error.h"
#include "splat_lod/core/parallel_for.h"
#include "splat_lod/core/world_lock.h"
#include "splat_lod/worldgen/world_meshes.h"
#include "world_build.h"
#include "world_folder.h"
#include "world_layout.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;

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

bool groups_current(const WorldManifest& m, const WorldOptions& o, std::string* why_not) {
    const auto no = [&](const std::string& why) {
        if (why_not) *why_not = why;
        return false;
    };
    const fs::path path = o.output / kManifestFileName;
    if (m.group_generator != group_generator_settings(o.groups))
        return no(path.string() + ": its chunk groups were made with other settings (or it has none)");
    std::error_code ec;
    for (const auto& g : m.groups) {
        const auto size = fs::file_size(o.output / g.file, ec);
        if (ec || size != g.file_bytes) return no((o.output / g.file).string() + ": missing or not the recorded size");
    }
    return true;
}

WorldSummary count_world_content(const WorldOptions& o) {
    validate(o);
    const auto start = Clock::now();
    const WorldTerrain terrain(o.seed, o.size_m, WorldTerrain::feature_scale_for(o.size_m));
    const WorldLayout layout = make_world_layout(terrain, o.seed);
    const ContentContext context = content_context(o, terrain, layout);
    const std::vector<ChunkSlot> slots = chunk_slots(o);
    std::vector<ContentCounts> counts(slots.size());
    std::vector<std::uint64_t> sizes(slots.size());
    reference::detail::parallel_for(
        slots.size(), reference::detail::resolve_thread_count(o.threads),
        [&](std::size_t k) { sizes[k] = make_chunk_content(context, slots[k].square, &counts[k]).size(); });
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
    const WorldTerrain terrain(o.seed, o.size_m, WorldTerrain::feature_scale_for(o.size_m));
    const WorldLayout layout = make_world_layout(terrain, o.seed);
    write_prop_meshes(o.output / generation);
    if (o.terrain_mesh) write_terrain_mesh(o.output / generation, terrain);
    s.stages.push_back({"layout and meshes", seconds_since(stage_start)});

    stage_start = Clock::now();
    std::vector<ChunkResult> chunks =
        build_chunks(o, content_context(o, terrain, layout), generation, chunk_slots(o), start);
    s.stages.push_back({"chunks (content, bake, write)", seconds_since(stage_start)});

    WorldManifest m = manifest_without_chunks(o, layout, generation);
    add_chunk_results(chunks, m, s);
    add_groups(o, generation, m, s, start);
    if (o.progress) o.progress({"manifest", m.chunks.size(), m.chunks.size(), 0, seconds_since(start), 0.0});
    return m;
}

// Writes the manifest (the commit) naming the files of `generation`, then removes what it does not name.
void commit(const WorldOptions& o, const fs::path& generation, const WorldManifest& m, WorldSummary& s,
            Clock::time_point start) {
    const auto stage_start = Clock::now();
    try {
        write_world_manifest(o.output / kManifestFileName, m);  // the commit
    } catch (...) {
        remove_generation_unless_committed(o.output, generation);
        throw;
    }
    if (o.progress) o.progress({"clean-up", m.chunks.size(), m.chunks.size(), 0, seconds_since(start), 0.0});
    remove_unnamed_files(o.output, m);
    s.stages.push_back({"manifest and clean-up", seconds_since(stage_start)});
}

// A cached world whose chunks match but whose groups do not: new groups in a new generation, the
// chunks and meshes named where they are.
WorldManifest rebuild_groups(const WorldOptions& o, WorldManifest cached, WorldSummary& s, Clock::time_point start) {
    const fs::path generation = new_generation(o.output);
    WorldManifest m = std::move(cached);
    m.version = kManifestVersion;
    try {
        add_groups(o, generation, m, s, start);
    } catch (...) {
        std::error_code ec;
        fs::remove_all(o.output / generation, ec);
        throw;
    }
    commit(o, generation, m, s, start);
    s.groups_rebuilt = true;
    return m;
}

}  // namespace

WorldResult generate_world(const WorldOptions& o) {
    validate(o);
    const auto start = Clock::now();
    WorldResult result;
    WorldSummary& s = result.summary;
    std::error_code ec;
    create_world_folder(o.output);
    // Held while this run writes or removes files (world_lock.h); a cached world needs no lock.
    const WorldFolderLock lock(o.output, WorldFolderLock::Mode::write);
    if (!o.force) {
        if (auto cached = find_cached_world(o, &s.cache_note)) {
            if (groups_current(*cached, o, &s.cache_note)) {
                // What a run killed between its commit and its clean-up left (unless a run is busy here).
                if (lock.held()) remove_unnamed_files(o.output, *cached);
                result.manifest = std::move(*cached);
            } else {
                lock.require();
                result.manifest = rebuild_groups(o, std::move(*cached), s, start);
            }
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
    commit(o, generation, result.manifest, s, start);

    summarise_manifest(result.manifest, o.output, s);
    s.fine_gaussians = s.gaussians_per_level[0];
    s.seconds = seconds_since(start);
    return result;
}

}  // namespace splat_lod::world
