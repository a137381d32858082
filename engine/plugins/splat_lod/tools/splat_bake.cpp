// splat_bake: trained splat scene → LOD asset (INRIA PLY with lod_level, coverage_min, coverage_max;
// coarse levels first). docs/algorithms.md §4.
//   splat_bake --input scene.ply --output scene.lod.ply [--cameras auto|rings:RxA|orbit:N|cameras.json|path.json]
//              [--up X,Y,Z] [--width 512 --height 384] [--levels 4] [--size-threshold 2]
//              [--refine-iterations 200] [--refine-cameras 16] [--threads N] [--seed N]
// The output is written only when the whole bake succeeded, through a temporary file in the same
// folder ("<output>.tmp-<pid>-<n>", synced to disk) and a rename (engine::write_file_atomic), so a
// failed or killed bake leaves any previous output byte for byte. A bake killed during that write
// leaves its temporary behind; the next successful bake to the same output removes it.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "engine/core/cli_values.h"
#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_lod/bake/bake.h"
#include "splat_lod/bake/bake_cameras.h"
#include "splat_lod/core/splat_io.h"

namespace {

struct Options {
    std::string input, output, cameras = "auto", up = "0,1,0", cells = "auto", pooling = "mean";
    int width = 512;
    int height = 384;
    bool keep_ranges = false;
    splat_lod::bake::BakeOptions bake;
};

// Fails before the (long) bake when the output cannot be written: its folder must exist and
// accept a new file. The probe file is removed again.
void check_output_writable(const std::filesystem::path& output, const std::filesystem::path& input) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(output, ec) && fs::is_directory(output, ec))
        engine::fail(output.string() + ": is a folder; give the output file's path");
    if (fs::exists(input, ec) && fs::exists(output, ec) && fs::equivalent(input, output, ec))
        engine::fail(output.string() + ": the output would replace the input; choose another file");
    const fs::path folder = output.parent_path().empty() ? fs::path(".") : output.parent_path();
    if (!fs::is_directory(folder, ec))
        engine::fail(output.string() + ": the folder " + folder.string() + " does not exist");
    const fs::path probe = folder / (".splat_bake_probe_" + std::to_string(::getpid()));
    std::FILE* file = std::fopen(probe.c_str(), "wb");
    if (file == nullptr) engine::fail(output.string() + ": cannot write in " + folder.string());
    std::fclose(file);
    fs::remove(probe, ec);
}

int run(Options& o) {
    namespace bake = splat_lod::bake;
    check_output_writable(o.output, o.input);
    bake::validate(o.bake);

    const auto start = std::chrono::steady_clock::now();
    splat_lod::LoadReport report;
    const splat_lod::SplatCloud fine = splat_lod::load_splat_file(o.input, &report);
    std::fprintf(stderr, "splat_bake: %s: %zu Gaussians (%s, SH degree %d)", o.input.c_str(), fine.size(),
                 report.format.c_str(), fine.sh_degree);
    if (report.dropped() > 0) std::fprintf(stderr, ", %zu dropped (NaN/Inf or zero rotation)", report.dropped());
    std::fprintf(stderr, "\n");
    if (fine.empty()) engine::fail(o.input + ": the scene has no Gaussians to bake");

    const auto extent = splat_lod::eval::robust_extent(fine.positions);
    const auto poses = bake::bake_camera_poses(o.cameras, extent, engine::parse_vec3(o.up, "--up"));
    const auto cameras = bake::bake_cameras(poses, o.width, o.height);
    std::fprintf(stderr, "splat_bake: %zu cameras (%s) at %dx%d\n", cameras.size(), o.cameras.c_str(), o.width,
                 o.height);

    std::string last_stage;
    int last_percent = -1;
    o.bake.progress = [&](const std::string& stage, double fraction) {
        const int percent = static_cast<int>(fraction * 100.0);
        if (stage == last_stage && percent / 10 == last_percent / 10 && percent != 100) return;
        last_stage = stage;
        last_percent = percent;
        std::fprintf(stderr, "splat_bake: %-24s %3d%%\n", stage.c_str(), percent);
    };

    bake::BakeSummary summary;
    splat_lod::SplatCloud baked;
    try {
        baked = bake::bake_lod(fine, cameras, o.bake, &summary);
    } catch (const engine::Error& e) {
        engine::fail(o.input + ": " + e.what());
    }
    splat_lod::write_inria_ply(o.output, baked);
    if (const std::size_t stale = engine::remove_stale_temporaries(o.output); stale > 0)
        std::fprintf(stderr, "splat_bake: removed %zu temporary file(s) of killed bakes beside %s\n", stale,
                     o.output.c_str());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stdout, "%s", bake::format_summary(summary).c_str());
    std::fprintf(stdout, "wrote %s (%zu Gaussians) in %.1f s\n", o.output.c_str(), baked.size(), seconds);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Bake levels of detail (multi-scale 3DGS) into a trained splat scene"};
    app.add_option("--input", o.input, "trained scene (.ply, .compressed.ply, .splat, .spz, SOG meta.json)")
        ->required();
    app.add_option("--output", o.output, "LOD asset to write (INRIA PLY)")->required();
    app.add_option("--cameras", o.cameras,
                   "auto (rings:3x8), rings:RxA, orbit:N, an INRIA cameras.json or a camera-path JSON");
    app.add_option("--up", o.up, "the scene's up direction for generated cameras X,Y,Z (Y-down captures: 0,-1,0)");
    app.add_option("--width", o.width, "bake camera width in pixels (refinement needs a multiple of 64)")
        ->check(CLI::Range(1, 16384));
    app.add_option("--height", o.height, "bake camera height in pixels (refinement needs a multiple of 64)")
        ->check(CLI::Range(1, 16384));
    app.add_option("--levels", o.bake.coarsest_level, "coarsest level to build (1..4)")->check(CLI::Range(1, 4));
    app.add_option("--size-threshold", o.bake.size_threshold_px, "S_T in pixels");
    app.add_option("--refine-iterations", o.bake.refine_iterations, "Adam iterations per coarse level (0: off)")
        ->check(CLI::Range(0, 100000));
    app.add_option("--refine-cameras", o.bake.refine_cameras, "at most this many cameras for the refinement")
        ->check(CLI::Range(1, 10000));
    auto* enlargement = app.add_option("--max-enlargement", o.bake.max_enlargement,
                                       "clamp of the pooled Gaussians' enlargement S_T / S_avg (fixes the recipe)")
                            ->check(CLI::Range(1.0, 1000.0));
    app.add_option("--pooling", o.pooling, "mean (docs/algorithms.md §4 steps 4-5) or moments (moment-matched cells)")
        ->check(CLI::IsMember({"mean", "moments"}));
    auto* cells = app.add_option("--cells", o.cells,
                                 "auto (bake both recipes, keep the better), adaptive (the larger of grid and "
                                 "distance cells, enlargement <= 8) or grid (docs/algorithms.md §4 step 3, "
                                 "enlargement <= 32)")
                      ->check(CLI::IsMember({"auto", "adaptive", "grid"}));
    app.add_flag("--keep-ranges", o.keep_ranges, "do not measure the coverage ranges again after the refinement");
    app.add_option("--debug-images", o.bake.debug_image_dir,
                   "folder (existing) for the refinement's target/before/after PNGs of its first camera");
    app.add_option("--threads", o.bake.threads, "worker threads (0: all cores)")->check(CLI::Range(0, 1024));
    app.add_option("--seed", o.bake.seed, "seed of the refinement's camera order");
    CLI11_PARSE(app, argc, argv);
    o.bake.ranges_after_refine = !o.keep_ranges;
    o.bake.pooling =
        o.pooling == "moments" ? splat_lod::bake::PoolingRule::moments : splat_lod::bake::PoolingRule::mean;
    o.bake.cells = o.cells == "grid" ? splat_lod::bake::CellRule::grid : splat_lod::bake::CellRule::adaptive;
    o.bake.choose_recipe = o.cells == "auto" && enlargement->count() == 0;
    if (cells->count() > 0 && o.cells != "auto" && enlargement->count() == 0)
        o.bake.max_enlargement = o.cells == "grid" ? 32.0 : 8.0;
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "splat_bake: %s\n", e.what());
        return 1;
    }
}
