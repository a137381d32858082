#include "tiny_world.h"

#include <fstream>
#include <iterator>
#include <regex>

#include "splat_lod/core/world_manifest.h"
#include "test_support.h"

namespace engine::test {

std::filesystem::path cached_tiny_world(const std::string& name) {
    const auto folder = output_root() / "sample_game" / name;
    splat_lod::world::generate_world(tiny_world_options(folder));
    return folder;
}

splat_lod::world::WorldOptions tiny_world_options(const std::filesystem::path& folder, std::uint64_t seed,
                                                  int threads) {
    splat_lod::world::WorldOptions o;
    o.seed = seed;
    o.size_m = 96.0f;
    o.chunk_size_m = 32.0f;
    o.density = 0.1f;
    o.threads = threads;
    o.bake.refine_iterations = 3;
    o.bake.refine_cameras = 4;
    o.bake_width = 128;
    o.bake_height = 128;
    o.output = folder;
    return o;
}

std::map<std::string, std::string> folder_bytes(const std::filesystem::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& item : std::filesystem::recursive_directory_iterator(folder))
        if (item.is_regular_file()) {
            std::ifstream in(item.path(), std::ios::binary);
            files[std::filesystem::relative(item.path(), folder).generic_string()] =
                std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        }
    return files;
}

std::map<std::string, std::string> without_generation(const std::map<std::string, std::string>& files) {
    const std::regex generation("gen-[0-9]+/");
    std::map<std::string, std::string> result;
    for (const auto& [name, bytes] : files) {
        const bool manifest = name == splat_lod::world::kManifestFileName;
        result[std::regex_replace(name, generation, "")] = manifest ? std::regex_replace(bytes, generation, "") : bytes;
    }
    return result;
}

}  // namespace engine::test
