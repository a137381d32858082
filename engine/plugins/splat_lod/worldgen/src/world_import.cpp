// import_world(): survey, binning, chunk bakes, far layer, groups, commit (world_import.h); the steps are
// in world_import_steps.cpp, shared with sharded imports (world_import_shards.cpp).
#include "splat_lod/worldgen/world_import.h"

#include <cstdio>
#include <sstream>
#include <system_error>

#include "engine/core/error.h"
#include "engine/core/process_memory.h"
#include "splat_lod/core/world_lock.h"
#include "world_folder.h"
#include "world_import_steps.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;

// Everything below `generation`; returns the manifest that names it.
WorldManifest build_import(const ImportOptions& o, const ImportPlan& plan, const fs::path& generation, ImportSummary& s,
                           Clock::time_point start) {
    WorldOptions w;
    WorldManifest m =
        bake_capture(o, plan, o.output, generation, o.output / generation / "bins", {}, true, w, s, start);
    add_groups(w, generation, m, s.world, start);
    return m;
}

}  // namespace

ImportResult import_world(const ImportOptions& o) {
    const auto start = Clock::now();
    ImportResult result;
    ImportSummary& s = result.summary;
    ImportPlan plan = open_import(o, s);
    create_world_folder(o.output);
    const WorldFolderLock lock(o.output, WorldFolderLock::Mode::write);
    if (auto cached = cached_import(o, plan.fingerprint))
        return cached_import_result(std::move(*cached), o.output, start);
    lock.require();
    survey_import(o, plan, s, start);

    const fs::path generation = new_generation(o.output);
    auto stage = Clock::now();
    try {
        result.manifest = build_import(o, plan, generation, s, start);
        stage = Clock::now();
        if (o.progress) o.progress({"manifest", 0, 0, 0, seconds_since(start), -1.0});
        write_world_manifest(o.output / kManifestFileName, result.manifest);  // the commit
    } catch (...) {
        remove_generation_unless_committed(o.output, generation);
        throw;
    }
    remove_unnamed_files(o.output, result.manifest);
    s.world.stages.push_back({"manifest and clean-up", seconds_since(stage)});
    summarise_manifest(result.manifest, o.output, s.world);
    s.world.seconds = seconds_since(start);
    s.peak_rss_bytes = engine::process_memory().peak_resident_bytes;
    return result;
}

std::string format_import_summary(const ImportSummary& s) {
    std::ostringstream out;
    char line[512];
    if (s.cached) {
        std::snprintf(line, sizeof line,
                      "cached import: %zu chunks, %llu Gaussians on disk (the capture's files and "
                      "the options are unchanged; --force imports again)\n",
                      s.world.chunks, static_cast<unsigned long long>(s.world.gaussians));
        return line;
    }
    std::snprintf(line, sizeof line, "capture: %s, %llu Gaussians read\n", s.capture_description.c_str(),
                  static_cast<unsigned long long>(s.read));
    out << line;
    std::snprintf(
        line, sizeof line,
        "frame: up (%.4f, %.4f, %.4f) from %s, translation (%.3f, %.3f, %.3f), %s views (height span %.2f %%, "
        "median extent %.2g of the footprint)\n",
        s.up.x, s.up.y, s.up.z, s.up_source.c_str(), s.translation.x, s.translation.y, s.translation.z,
        s.aerial ? "aerial" : "ground", 100.0 * s.flatness, s.coarseness);
    out << line;
    std::snprintf(line, sizeof line, "grid: %.4g units square, chunks of %.4g units (scale %.4g)\n",
                  static_cast<double>(s.size), static_cast<double>(s.chunk_size), static_cast<double>(s.scale));
    out << line;
    if (s.run != "merged world") {  // the merge bins nothing: its shards did
        const auto n = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
        std::snprintf(
            line, sizeof line,
            "Gaussians: %llu in chunks; dropped: %llu by the reader (NaN/Inf, zero rotation), %llu never visible, "
            "%llu degenerate; far layer: %llu huge + %llu outside the world box, %llu kept, %llu dropped over its cap; "
            "%zu chunks seen by no bake camera, kept unbaked\n",
            n(s.binned), n(s.dropped_by_reader), n(s.invisible), n(s.degenerate), n(s.far_huge), n(s.far_outside),
            n(s.far_layer), n(s.far_dropped), s.unbaked_chunks);
        out << line;
        if (s.merged_chunks > 0) {  // --quadtree
            std::snprintf(line, sizeof line,
                          "quadtree: %zu chunks merged from sparse cells, the largest %d x %d cells\n", s.merged_chunks,
                          1 << s.largest_span, 1 << s.largest_span);
            out << line;
        }
        if (s.training_cameras > 0) {
            std::snprintf(line, sizeof line,
                          "training cameras: %zu read; %zu chunks baked from them, the rest from the rings\n",
                          s.training_cameras, s.training_camera_chunks);
            out << line;
        }
    }
    std::string world = format_summary(s.world);
    // The world's own summary speaks of generated content; an import has none.
    if (world.rfind("generated world:", 0) == 0) world.replace(0, 15, s.run);
    if (const auto none = world.find(" (0 generated)"); none != std::string::npos)
        world.replace(none, 14, s.binned > 0 ? " (" + std::to_string(s.binned) + " from the capture)" : "");
    const auto generated_line = world.find("  generated: ");
    if (generated_line != std::string::npos)
        world.erase(generated_line, world.find('\n', generated_line) + 1 - generated_line);
    out << world;
    std::snprintf(line, sizeof line, "peak resident memory %.2f GiB\n",
                  static_cast<double>(s.peak_rss_bytes) / (1024.0 * 1024.0 * 1024.0));
    out << line;
    return out.str();
}

}  // namespace splat_lod::world
