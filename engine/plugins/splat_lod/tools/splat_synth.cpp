// splat_synth: writes the procedural fine-detail garden (foliage, picket fence, grass) as an INRIA PLY.
//   splat_synth --out scene.ply [--seed N] [--detail F]
// Prints the Gaussian count, the bounds and the generation time. Exit code 1 on any error,
// including bad options; a failed write leaves no partial file (the writer is atomic).
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
#include "splat_lod/core/splat_io.h"
#include "splat_lod/synth/fine_detail_scene.h"

namespace {

struct Options {
    std::string out, seed_text = "1";
    float detail = 1.0f;
};

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
    const splat_lod::SplatCloud cloud = synth::make_fine_detail_scene({seed, o.detail});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    splat_lod::write_inria_ply(o.out, cloud);

    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const auto& p : cloud.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    std::printf("%s: %zu Gaussians (seed %llu, detail %g, generated in %.2f s)\n", o.out.c_str(), cloud.size(),
                static_cast<unsigned long long>(seed), static_cast<double>(o.detail), seconds);
    std::printf("  bounds min (%.3f, %.3f, %.3f) max (%.3f, %.3f, %.3f) m, Y up\n", static_cast<double>(lo.x),
                static_cast<double>(lo.y), static_cast<double>(lo.z), static_cast<double>(hi.x),
                static_cast<double>(hi.y), static_cast<double>(hi.z));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Write the procedural fine-detail splat garden (trees, picket fence, grass) as an INRIA PLY"};
    app.add_option("--out", o.out, "output .ply file")->required();
    app.add_option("--seed", o.seed_text, "random seed, 0 to 2^64 - 1 (the same seed gives the same bytes)");
    app.add_option("--detail", o.detail, "density factor in [0.01, 16]; 1 gives about 195k Gaussians");
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
