// splat_world: generates and bakes the sample world into a folder (world/world_generator.h), or
// reuses the world already there when it was made with the same options.
//   splat_world --out DIR [--seed N] [--size M] [--chunk M] [--density F] [--threads N]
//               [--refine-iterations N] [--bake-width W --bake-height H] [--no-terrain-mesh] [--force]
//               [--count-only | --shard I/N | --merge]
// Progress (chunks done, Gaussians, elapsed, ETA) goes to stderr, the summary (chunks, Gaussians per
// level, bytes, stage times) to stdout. Exit code 1 on any error.
//
// Output safety (world/world_generator.h): a run never touches the world already in --out until the
// new one is complete. It writes every file into a new folder --out/gen-<n>/ (chunks/, meshes/),
// each synced to disk, then replaces world.json atomically (the commit: world.json names the files
// by relative path), and only then removes the previous generation and leftovers of killed runs.
// Killed (Ctrl-C, SIGKILL, power loss) or failing at any point, it leaves the previous world.json
// and every file it names byte for byte, or the new world complete; the next run cleans up. Only
// one run at a time may write into a folder (a second fails with a message). Disk space: up to two
// worlds while a run replaces one.
//
// Sharded bakes (world/world_shards.h, docs/world_bakes.md): `--shard I/N` (I 1-based) bakes chunks
// k with k mod N = I - 1 into --out/staging-<hash>/ and writes the shard's record there; shards may
// run at once, on one machine or on several sharing the folder. `--merge`, once all are done,
// checks every chunk against its record and commits the world: the same bytes as an unsharded run.
// With --from CAPTURE (world/world_import.h) the shards are an import's: each reads the whole capture
// and bakes its chunks into --out/staging-import-<fingerprint>/; --merge with the same --from and
// options commits the imported world.
#include <cctype>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "engine/core/cli_values.h"
#include "engine/core/error.h"
#include "splat_lod/worldgen/world_generator.h"
#include "splat_lod/worldgen/world_import.h"
#include "splat_lod/worldgen/world_shards.h"

namespace {

std::string duration(double seconds) {
    if (seconds < 0.0) return "?";
    const auto s = static_cast<long long>(seconds + 0.5);
    char text[32];
    if (s >= 3600)
        std::snprintf(text, sizeof text, "%lldh%02lldm%02llds", s / 3600, s / 60 % 60, s % 60);
    else
        std::snprintf(text, sizeof text, "%lldm%02llds", s / 60, s % 60);
    return text;
}

// One line per chunk for small worlds; for large ones at most one every two seconds (and the last).
void print_progress(const splat_lod::world::WorldProgress& p) {
    static auto last = std::chrono::steady_clock::time_point{};
    const auto now = std::chrono::steady_clock::now();
    if (p.stage == "groups") {
        if (p.chunks_total > 16 && p.chunks_done != p.chunks_total && now - last < std::chrono::seconds(2)) return;
        last = now;
        std::fprintf(stderr, "splat_world: chunk groups %zu/%zu, %s elapsed\n", p.chunks_done, p.chunks_total,
                     duration(p.elapsed_seconds).c_str());
        return;
    }
    if (p.stage != "chunks") {
        std::fprintf(stderr, "splat_world: %s (%s elapsed)\n", p.stage.c_str(), duration(p.elapsed_seconds).c_str());
        return;
    }
    const bool last_chunk = p.chunks_done == p.chunks_total;
    if (p.chunks_total > 64 && !last_chunk && now - last < std::chrono::seconds(2)) return;
    last = now;
    std::fprintf(
        stderr, "splat_world: chunks %zu/%zu (%.1f%%), %llu Gaussians, %s elapsed, ETA %s\n", p.chunks_done,
        p.chunks_total,
        p.chunks_total ? 100.0 * static_cast<double>(p.chunks_done) / static_cast<double>(p.chunks_total) : 100.0,
        static_cast<unsigned long long>(p.gaussians), duration(p.elapsed_seconds).c_str(),
        duration(p.eta_seconds).c_str());
}

// The merge's summary: what it committed (the bake statistics stay with the shards that baked).
std::string merge_summary(const splat_lod::world::WorldSummary& s) {
    std::string text = "merged world: " + std::to_string(s.chunks) + " chunks, " + std::to_string(s.gaussians) +
                       " Gaussians on disk, " + std::to_string(s.props) + " props\n";
    for (int l = splat_lod::world::kLevels; l >= 1; --l)
        text += "  stream level " + std::to_string(l) + ": " +
                std::to_string(s.gaussians_per_stream_level[static_cast<std::size_t>(l - 1)]) + " Gaussians\n";
    char line[128];
    std::snprintf(line, sizeof line, "  bytes: chunks %.1f MiB, meshes %.2f MiB\n",
                  static_cast<double>(s.chunk_bytes) / 1048576.0, static_cast<double>(s.mesh_bytes) / 1048576.0);
    text += line;
    for (const auto& stage : s.stages) {
        std::snprintf(line, sizeof line, "  %-32s %6.1f s\n", stage.stage.c_str(), stage.seconds);
        text += line;
    }
    std::snprintf(line, sizeof line, "  total %.1f s\n", s.seconds);
    return text + line;
}

struct CommandLine {
    splat_lod::world::WorldOptions options;
    std::string out, seed_text = "1", shard_text;
    // --from: a capture imported instead of the generated world (world/world_import.h).
    std::string from, up_text = "auto", memory_text = "3G", views_text = "auto", codec_text = "compact";
    std::uint64_t max_chunk_gaussians = 262144;
    std::string cameras;
    bool no_terrain_mesh = false, no_groups = false, count_only = false, merge = false, quadtree = false;
    CLI::Option* shard_option = nullptr;  // given: bake a shard
};

splat_lod::world::ChunkCodec codec(const CommandLine& c) {
    return c.codec_text == "ply" ? splat_lod::world::ChunkCodec::ply : splat_lod::world::ChunkCodec::compact;
}

// What the world is and how its chunks are baked.
void add_world_options(CLI::App& app, CommandLine& c) {
    splat_lod::world::WorldOptions& options = c.options;
    app.add_option("--out", c.out, "the world's folder (world.json, gen-<n>/chunks/, gen-<n>/meshes/)")->required();
    app.add_option("--seed", c.seed_text, "random seed, 0 to 2^64 - 1 (the same seed gives the same bytes)");
    app.add_option("--size", options.size_m, "world size in metres (a multiple of --chunk); 1024 by default")
        ->check(CLI::Range(4.0, 65536.0));
    app.add_option("--chunk", options.chunk_size_m, "chunk size in metres; 64 by default")
        ->check(CLI::Range(4.0, 65536.0));
    app.add_option("--density", options.density, "scales every Gaussian count, (0, 8]; 1 by default")
        ->check(CLI::Range(0.0, 8.0));
    app.add_option("--threads", options.threads, "chunks baked at once (0: all cores)")->check(CLI::Range(0, 1024));
    app.add_option("--refine-iterations", options.bake.refine_iterations,
                   "Adam iterations per coarse level of each chunk's bake (0: off)")
        ->check(CLI::Range(0, 100000));
    app.add_option("--bake-width", options.bake_width, "chunk bake camera width (a multiple of 64)")
        ->check(CLI::Range(64, 8192));
    app.add_option("--bake-height", options.bake_height, "chunk bake camera height (a multiple of 64)")
        ->check(CLI::Range(64, 8192));
    app.add_flag("--no-terrain-mesh", c.no_terrain_mesh, "do not write the coarse terrain mesh");
    app.add_flag("--no-groups", c.no_groups, "no chunk groups (the far field is then drawn from every chunk)");
    app.add_option("--group-cell", options.groups.base_cell_m,
                   "the chunk groups' pooling cell at depth 1 in metres, doubling per depth; 1 by default")
        ->check(CLI::Range(0.01, 1000.0));
    app.add_option("--group-fill", options.groups.fill,
                   "widens the chunk groups' pooled Gaussians so that neighbours overlap, 1 to 4; 1.5 by default")
        ->check(CLI::Range(1.0, 4.0));
    app.add_option("--chunk-codec", c.codec_text,
                   "how chunk files store the Gaussians: compact (compressed, quantised; the default) or ply "
                   "(lossless, about 5x larger)")
        ->check(CLI::IsMember({"compact", "ply"}));
}

// Importing a capture (--from) instead of generating the sample world.
void add_import_options(CLI::App& app, CommandLine& c) {
    app.add_option("--from", c.from,
                   "import this capture instead of generating the sample world: a splat file, a streamed SOG "
                   "(lod-meta.json[#level]), a folder or .txt list of tiles");
    app.add_option("--up", c.up_text, "the capture's up direction: auto (found from the data) or X,Y,Z");
    app.add_option("--cameras", c.cameras,
                   "with --from: the capture's training cameras (cameras.json, COLMAP images.txt, or a folder with "
                   "either): chunks that 4 or more of them see are baked from those instead of the rings");
    app.add_option("--memory", c.memory_text, "resident memory the import stays within, e.g. 2G, 512M; 3G by default");
    app.add_option("--max-chunk-gaussians", c.max_chunk_gaussians,
                   "the chunk size is chosen so that no chunk holds more; 262144 by default (the generated world's 64 "
                   "m chunks hold up to 106k)")
        ->check(CLI::Range(std::uint64_t{1024}, std::uint64_t{1} << 26));
    app.add_flag("--quadtree", c.quadtree,
                 "with --from: merge sparse cells into larger chunks (fewer bakes; streams coarser near the camera)");
    app.add_option("--views", c.views_text, "chunk bake cameras: auto, ground (eye height and above) or aerial");
}

std::uint64_t parse_memory(const std::string& text) {
    std::uint64_t unit = 1;
    std::string digits = text;
    if (!digits.empty()) {
        const char last = static_cast<char>(std::toupper(static_cast<unsigned char>(digits.back())));
        if (last == 'G' || last == 'M' || last == 'K') {
            unit = last == 'G' ? (1u << 30) : last == 'M' ? (1u << 20) : (1u << 10);
            digits.pop_back();
        }
    }
    return engine::parse_u64(digits, "--memory") * unit;
}

int run_import(const CommandLine& c) {
    namespace world = splat_lod::world;
    if (c.count_only) throw engine::Error("--from: --count-only is for generated worlds (an import reads the capture)");
    world::ImportOptions o;
    o.capture = c.from;
    o.output = c.out;
    if (c.up_text != "auto") o.up = engine::parse_vec3(c.up_text, "--up");
    o.memory_bytes = parse_memory(c.memory_text);
    o.max_chunk_gaussians = c.max_chunk_gaussians;
    o.quadtree = c.quadtree;
    o.cameras = c.cameras;
    if (c.views_text == "ground")
        o.views = world::CaptureViews::ground;
    else if (c.views_text == "aerial")
        o.views = world::CaptureViews::aerial;
    else if (c.views_text != "auto")
        throw engine::Error("--views \"" + c.views_text + "\": expected auto, ground or aerial");
    o.threads = c.options.threads;
    o.bake = c.options.bake;
    o.bake_width = c.options.bake_width;
    o.bake_height = c.options.bake_height;
    o.groups = !c.no_groups;
    o.chunk_codec = codec(c);
    o.force = c.options.force;
    o.progress = print_progress;
    const auto shard =
        c.shard_option->count() > 0 ? std::optional(world::parse_world_shard(c.shard_text)) : std::nullopt;
    const world::ImportResult result = shard     ? world::import_world_shard(o, *shard)
                                       : c.merge ? world::merge_import_shards(o)
                                                 : world::import_world(o);
    std::printf("%s", world::format_import_summary(result.summary).c_str());
    if (shard && !result.summary.cached)
        std::printf("shard %zu/%zu: %s\n", shard->index, shard->count, result.record.string().c_str());
    else
        std::printf("world: %s\n", (o.output / world::kManifestFileName).string().c_str());
    return 0;
}

// What to do: the whole world, a count, a shard or the merge of the shards.
void add_run_options(CLI::App& app, CommandLine& c) {
    app.add_flag("--force", c.options.force, "regenerate even when the cached world matches");
    auto* count_flag = app.add_flag("--count-only", c.count_only,
                                    "only generate the content and print its Gaussian counts (no bake, no files)");
    c.shard_option = app.add_option("--shard", c.shard_text,
                                    "bake only shard I of N (I is 1-based: 1..N), chunks k with k mod N = I - 1, "
                                    "into --out/staging-<hash>/; then --merge")
                         ->excludes(count_flag);
    app.add_flag("--merge", c.merge, "commit the world that --shard runs baked into --out (all must be done)")
        ->excludes(count_flag)
        ->excludes(c.shard_option);
}

int run(CommandLine& c) {
    namespace world = splat_lod::world;
    if (!c.from.empty()) return run_import(c);
    const auto shard = c.shard_option->count() > 0 ? std::optional(world::parse_world_shard(c.shard_text))  // first
                                                   : std::optional<world::WorldShard>();
    world::WorldOptions& options = c.options;
    options.seed = engine::parse_u64(c.seed_text, "--seed");
    options.output = c.out;
    options.terrain_mesh = !c.no_terrain_mesh;
    options.groups.enabled = !c.no_groups;
    options.chunk_codec = codec(c);
    options.progress = print_progress;
    if (c.count_only) {
        std::printf("%s", world::format_summary(world::count_world_content(options)).c_str());
        return 0;
    }
    const auto result = shard     ? world::bake_world_shard(options, *shard)
                        : c.merge ? world::merge_world_shards(options)
                                  : world::generate_world(options);
    if (!result.summary.cached && !result.summary.cache_note.empty())
        std::fprintf(stderr, "splat_world: not cached: %s\n", result.summary.cache_note.c_str());
    const bool merged = c.merge && !result.summary.cached;
    std::printf("%s", (merged ? merge_summary(result.summary) : world::format_summary(result.summary)).c_str());
    const auto record = shard ? options.output / world::staging_folder(options) / world::shard_record_name(*shard)
                              : std::filesystem::path();
    if (shard && std::filesystem::exists(record))
        std::printf("shard %zu/%zu: %s\n", shard->index, shard->count, record.string().c_str());
    else
        std::printf("world: %s\n", (options.output / world::kManifestFileName).string().c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CommandLine c;
    CLI::App app{"Generate and bake the sample world of LOD splat chunks and glTF props (cached in --out)"};
    add_world_options(app, c);
    add_run_options(app, c);
    add_import_options(app, c);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // CLI11 prints the message; its own exit codes (100+) are folded into the tools' 1.
        return app.exit(e) == 0 ? 0 : 1;
    }
    try {
        return run(c);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "splat_world: %s\n", e.what());
        return 1;
    }
}
