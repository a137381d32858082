// The world generator's options: defaults, checks, the settings string the cache compares, and
// the printed summary (world/world_generator.h).
#include <cmath>
#include <cstdio>
#include <sstream>

#include "engine/core/error.h"
#include "splat_lod/synth/world_terrain.h"
#include "splat_lod/worldgen/world_generator.h"

namespace splat_lod::world {
namespace {

// Bumped whenever the generated content changes for the same options, so that cached worlds made
// by an older generator are regenerated rather than reused.
constexpr int kContentVersion = 2;

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

}  // namespace

bake::BakeOptions default_world_bake_options() {
    bake::BakeOptions options;
    options.choose_recipe = false;
    options.cells = bake::CellRule::adaptive;
    options.max_enlargement = 8.0;
    options.refine_iterations = 60;
    options.refine_cameras = 8;
    options.threads = 1;
    options.range_low_percentile = 75.0;
    return options;
}

void validate(const WorldOptions& o) {
    const auto bad = [](const std::string& what) { engine::fail("world options: " + what); };
    if (!(std::isfinite(o.size_m) && o.size_m > 0.0f && o.size_m <= 65536.0f)) bad("the size must be in (0, 65536] m");
    if (!(std::isfinite(o.chunk_size_m) && o.chunk_size_m >= 4.0f && o.chunk_size_m <= o.size_m))
        bad("the chunk size must be at least 4 m and at most the world's size");
    const float chunks = std::round(o.size_m / o.chunk_size_m);
    if (chunks * o.chunk_size_m != o.size_m)
        bad("the size (" + number(o.size_m) + " m) must be a whole multiple of the chunk size (" +
            number(o.chunk_size_m) + " m)");
    if (chunks > static_cast<float>(kMaxChunksPerSide))
        bad("at most " + std::to_string(kMaxChunksPerSide) + " chunks per side");
    if (!(std::isfinite(o.density) && o.density > 0.0f && o.density <= 8.0f)) bad("the density must be in (0, 8]");
    if (o.threads < 0 || o.threads > 1024) bad("threads must be 0..1024");
    if (o.bake_width < 64 || o.bake_height < 64 || o.bake_width > 8192 || o.bake_height > 8192)
        bad("bake camera images must be 64..8192 pixels per side");
    if (o.output.empty()) bad("no output folder");
    bake::validate(o.bake);
    if (const std::string problem = check_group_options(o.groups, o.chunk_size_m); !problem.empty())
        bad("chunk groups: " + problem);
    if (const std::string problem = check_stream_level_rule(stream_level_rule(o)); !problem.empty())
        bad("stream levels: " + problem);
}

StreamLevelRule stream_level_rule(const WorldOptions& o) {
    StreamLevelRule rule;
    rule.lod = o.bake.rule;
    rule.reach_min = o.stream_reach_min;
    return rule;
}

std::string generator_settings(const WorldOptions& o) {
    const bake::BakeOptions& b = o.bake;
    std::ostringstream s;
    s << "splat_lod world content " << kContentVersion << "; bake " << o.bake_width << "x" << o.bake_height
      << " rings 3x8; levels " << b.coarsest_level << ", S_T " << number(b.rule.size_threshold_px) << ", rel "
      << number(b.rule.rel_min) << "/" << number(b.rule.rel_max) << ", znear " << number(b.znear) << ", "
      << (b.choose_recipe ? "chosen recipe"
                          : std::string(b.cells == bake::CellRule::grid ? "grid" : "adaptive") +
                                " cells, enlargement <= " + number(b.max_enlargement))
      << ", " << (b.pooling == bake::PoolingRule::moments ? "moments" : "mean") << " pooling, grid " << b.grid_cells
      << ", ranges " << number(b.range_low_percentile) << "-" << number(b.range_high_percentile) << "; refine "
      << b.refine_iterations << " x " << b.refine_cameras << " cameras, lr " << number(b.learning_rate_dc) << "/"
      << number(b.learning_rate_opacity) << ", clamp " << number(b.logit_clamp)
      << (b.ranges_after_refine ? ", ranges after" : "") << ", seed " << b.seed << "; terrain mesh "
      << (o.terrain_mesh ? "yes" : "no") << "; stream reach " << number(o.stream_reach_min[0]) << "/"
      << number(o.stream_reach_min[1]) << "/" << number(o.stream_reach_min[2]) << "; chunk files "
      << (o.chunk_codec == ChunkCodec::compact ? "compact" : "ply");
    // Worlds up to the largest feature scale have the feature scale of their size, and worlds larger
    // than that were once made with their own: only the larger ones say which they have.
    if (const float feature = WorldTerrain::feature_scale_for(o.size_m); feature != o.size_m)
        s << "; features " << number(feature) << " m";
    return s.str();
}

namespace {

// The summary's first lines: Gaussians on disk, per bake and stream level, and what was generated.
void summary_counts(const WorldSummary& s, std::ostringstream& out) {
    char line[256];
    if (s.cached)
        std::snprintf(line, sizeof line, "cached world: %zu chunks, %llu Gaussians on disk, %zu props\n", s.chunks,
                      static_cast<unsigned long long>(s.gaussians), s.props);
    else
        std::snprintf(line, sizeof line,
                      "generated world: %zu chunks, %llu Gaussians on disk (%llu generated), %zu props\n", s.chunks,
                      static_cast<unsigned long long>(s.gaussians), static_cast<unsigned long long>(s.fine_gaussians),
                      s.props);
    out << line;
    for (int l = kLevels; l >= 1; --l) {
        const auto i = static_cast<std::size_t>(l - 1);
        if (s.cached)
            std::snprintf(line, sizeof line, "  stream level %d: %llu Gaussians\n", l,
                          static_cast<unsigned long long>(s.gaussians_per_stream_level[i]));
        else
            std::snprintf(line, sizeof line, "  level %d: %llu Gaussians; stream level %d: %llu\n", l,
                          static_cast<unsigned long long>(s.gaussians_per_level[i]), l,
                          static_cast<unsigned long long>(s.gaussians_per_stream_level[i]));
        out << line;
    }
    if (!s.cached) {
        std::snprintf(line, sizeof line,
                      "  generated: ground %llu, water %llu, %llu trees (%llu), grass %llu, rocks %llu, fences %llu\n",
                      static_cast<unsigned long long>(s.ground), static_cast<unsigned long long>(s.water),
                      static_cast<unsigned long long>(s.trees), static_cast<unsigned long long>(s.tree_gaussians),
                      static_cast<unsigned long long>(s.grass), static_cast<unsigned long long>(s.rocks),
                      static_cast<unsigned long long>(s.fences));
        out << line;
    }
}

// The coarse levels' quality over the bake views, and the bytes of chunks, meshes and groups.
void summary_quality_and_bytes(const WorldSummary& s, std::ostringstream& out) {
    char line[256];
    for (int l = 2; l <= kLevels; ++l) {
        const auto i = static_cast<std::size_t>(l - 1);
        if (s.mean_level_psnr[i] == 0.0) continue;
        std::snprintf(line, sizeof line,
                      "  level %d at 1/%d: mean PSNR %.2f dB (level 1 alone %.2f dB) over the chunks' bake views\n", l,
                      bake::level_scale(l), s.mean_level_psnr[i], s.mean_baseline_psnr[i]);
        out << line;
    }
    std::snprintf(line, sizeof line, "  bytes: chunks %.1f MiB, meshes %.2f MiB\n",
                  static_cast<double>(s.chunk_bytes) / (1024.0 * 1024.0),
                  static_cast<double>(s.mesh_bytes) / (1024.0 * 1024.0));
    out << line;
    std::snprintf(line, sizeof line, "  chunk groups: %zu%s, %llu Gaussians, %.1f MiB\n", s.groups,
                  s.groups_rebuilt ? " (built for the cached chunks)" : "",
                  static_cast<unsigned long long>(s.group_gaussians),
                  static_cast<double>(s.group_bytes) / (1024.0 * 1024.0));
    out << line;
}

// The time of every stage, and of the per-chunk work summed over the workers.
void summary_times(const WorldSummary& s, std::ostringstream& out) {
    char line[256];
    for (const auto& stage : s.stages) {
        std::snprintf(line, sizeof line, "  %-28s %9.1f s\n", stage.stage.c_str(), stage.seconds);
        out << line;
    }
    if (!s.chunk_stages.empty()) out << "  per-chunk work, summed over chunks (worker seconds):\n";
    for (const auto& stage : s.chunk_stages) {
        std::snprintf(line, sizeof line, "    %-26s %9.1f s\n", stage.stage.c_str(), stage.seconds);
        out << line;
    }
    std::snprintf(line, sizeof line, "  total %.1f s\n", s.seconds);
    out << line;
}

}  // namespace

std::string format_summary(const WorldSummary& s) {
    std::ostringstream out;
    summary_counts(s, out);
    summary_quality_and_bytes(s, out);
    summary_times(s, out);
    return out.str();
}

}  // namespace splat_lod::world
