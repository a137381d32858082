// splat_convert: any splat file the engine reads → INRIA PLY or glTF with KHR_gaussian_splatting.
//   splat_convert --input FILE --output OUT.ply|OUT.glb|OUT.gltf
// No axis conversion: the Gaussians keep the input's own frame (docs/gltf_splats.md). The output is
// written through a temporary file and a rename, so a failed conversion leaves any previous output.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include <CLI/CLI.hpp>

#include "engine/core/error.h"
#include "splat_lod/core/splat_io.h"

namespace {

int run(const std::string& input, const std::string& output) {
    std::string ext = std::filesystem::path(output).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext != ".ply" && ext != ".glb" && ext != ".gltf")
        engine::fail(output + ": the output must end in .ply, .glb or .gltf");
    std::error_code ec;
    if (std::filesystem::exists(output, ec) && std::filesystem::equivalent(input, output, ec))
        engine::fail(output + ": the output would replace the input; choose another file");
    splat_lod::LoadReport report;
    const splat_lod::SplatCloud cloud = splat_lod::load_splat_file(input, &report);
    for (const auto& warning : report.warnings)
        std::fprintf(stderr, "splat_convert: %s: %s\n", input.c_str(), warning.c_str());
    if (report.dropped() > 0)
        std::fprintf(stderr, "splat_convert: %s: %zu Gaussians dropped (NaN/Inf or zero rotation)\n", input.c_str(),
                     report.dropped());
    if (cloud.empty()) engine::fail(input + ": no Gaussians to write");
    splat_lod::write_splat_file(output, cloud);
    std::fprintf(stdout, "wrote %s (%zu Gaussians, SH degree %d, from %s)\n", output.c_str(), cloud.size(),
                 cloud.sh_degree, report.format.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::string input, output;
    CLI::App app{"Convert a splat file to INRIA PLY or glTF (KHR_gaussian_splatting)"};
    app.add_option("--input", input, "splat file (.ply, .compressed.ply, .splat, .spz, SOG, .glb, .gltf)")->required();
    app.add_option("--output", output, "file to write: .ply (INRIA PLY), .glb or .gltf (KHR_gaussian_splatting)")
        ->required();
    CLI11_PARSE(app, argc, argv);
    try {
        return run(input, output);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "splat_convert: %s\n", e.what());
        return 1;
    }
}
