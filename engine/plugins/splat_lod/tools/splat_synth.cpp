// splat_synth: writes a procedural test scene as an INRIA PLY: the fine-detail garden (foliage, picket
// fence, grass; the default) or the forward-facing room with its capture's camera grid and held-out views.
//   splat_synth --out scene.ply [--scene garden|room] [--seed N] [--detail F]
//               [--cameras-out capture.json] [--held-out-out held_out.json]   (room only)
// Prints the Gaussian count, the bounds and the generation time. Exit code 1 on any error,
// including bad options; a failed write leaves no partial file (the writers are atomic).
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "engine/core/cli_values.h"
#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/synth/fine_detail_scene.h"
#include "splat_lod/synth/room_scene.h"

namespace {

struct Options {
    std::string out, scene = "garden", seed_text = "1", cameras_out, held_out_out;
    float detail = 1.0f;
};

splat_lod::SplatCloud make_scene(const Options& o, std::uint64_t seed) {
    namespace synth = splat_lod::synth;
    if (o.scene == "room") return synth::make_room_scene({seed, o.detail});
    if (!o.cameras_out.empty() || !o.held_out_out.empty())
        engine::fail("--cameras-out and --held-out-out need --scene room (the garden has no capture of its own)");
    return synth::make_fine_detail_scene({seed, o.detail});
}

// The room's capture grid and held-out views as camera-path JSON, when asked for.
void write_cameras(const Options& o) {
    namespace synth = splat_lod::synth;
    if (!o.cameras_out.empty()) {
        const auto poses = synth::room_capture_cameras();
        engine::write_text_file_atomic(o.cameras_out, synth::camera_path_json(poses));
        std::printf("%s: %zu capture cameras (camera path)\n", o.cameras_out.c_str(), poses.size());
    }
    if (!o.held_out_out.empty()) {
        const auto poses = synth::room_held_out_cameras();
        engine::write_text_file_atomic(o.held_out_out, synth::camera_path_json(poses));
        std::printf("%s: %zu held-out cameras (camera path)\n", o.held_out_out.c_str(), poses.size());
    }
}

int run(const Options& o) {
    namespace synth = splat_lod::synth;
    // Checked here as well as in the library so that the message names the option.
    if (!(std::isfinite(o.detail) && o.detail >= synth::kMinDetail && o.detail <= synth::kMaxDetail)) {
        char message[96];
        std::snprintf(message, sizeof message, "--detail must be in [%g, %g], got %g",
                      static_cast<double>(synth::kMinDetail), static_cast<double>(synth::kMaxDetail),
                      static_cast<double>(o.detail));
        engine::fail(message);
    }
    const std::uint64_t seed = engine::parse_u64(o.seed_text, "--seed");
    const auto started = std::chrono::steady_clock::now();
    const splat_lod::SplatCloud cloud = make_scene(o, seed);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    splat_lod::write_inria_ply(o.out, cloud);
    write_cameras(o);

    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const auto& p : cloud.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    std::printf("%s: %s, %zu Gaussians (seed %llu, detail %g, generated in %.2f s)\n", o.out.c_str(), o.scene.c_str(),
                cloud.size(), static_cast<unsigned long long>(seed), static_cast<double>(o.detail), seconds);
    std::printf("  bounds min (%.3f, %.3f, %.3f) max (%.3f, %.3f, %.3f) m, Y up\n", static_cast<double>(lo.x),
                static_cast<double>(lo.y), static_cast<double>(lo.z), static_cast<double>(hi.x),
                static_cast<double>(hi.y), static_cast<double>(hi.z));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{
        "Write a procedural splat test scene as an INRIA PLY: the fine-detail garden (trees, picket fence, "
        "grass) or a forward-facing room"};
    app.add_option("--out", o.out, "output .ply file")->required();
    app.add_option("--scene", o.scene,
                   "garden (default: the fine-detail garden, about 195k Gaussians) or room (one side of a room as a "
                   "forward-facing capture sees it, about 164k Gaussians)")
        ->check(CLI::IsMember({"garden", "room"}));
    app.add_option("--cameras-out", o.cameras_out,
                   "room only: write the capture's camera grid (6x4 eyes) as a camera-path JSON");
    app.add_option("--held-out-out", o.held_out_out,
                   "room only: write 8 held-out views near the capture, none on its grid, as a camera-path JSON");
    app.add_option("--seed", o.seed_text, "random seed, 0 to 2^64 - 1 (the same seed gives the same bytes)");
    app.add_option("--detail", o.detail, "density factor in [0.01, 16]; the count is close to proportional");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // CLI11 prints the message; its own exit codes (100+) are folded into the tools' 1.
        return app.exit(e) == 0 ? 0 : 1;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "splat_synth: %s\n", e.what());
        return 1;
    }
}
