// PlayCanvas streamed SOG lod-meta.json through io::read_streamed_sog_meta (splat_lod/core/streamed_sog.h),
// written into the sandbox beside two chunk files it may name (0_0/meta.json, 1_0/meta.json).
// Contract: a description or engine::Error naming the file; every chunk file lies inside the sandbox;
// per level, each file's ranges are sorted by offset and never overlap, and the level's count is the
// sum of its ranges'.
#include <fstream>

#include "engine/core/error.h"
#include "splat_fuzz_support.h"
#include "splat_lod/core/streamed_sog.h"

namespace {

using splat_fuzz::require;

void check_level(const splat_lod::io::StreamedSogLevel& level) {
    std::uint64_t total = 0;
    for (const auto& file : level.files) {
        require(splat_fuzz::inside_sandbox(file.file), "chunk file " + file.file.string() + " is inside the folder");
        std::uint64_t sum = 0;
        for (std::size_t k = 0; k < file.ranges.size(); ++k) {
            sum += file.ranges[k].count;
            if (k > 0)
                require(file.ranges[k - 1].offset + file.ranges[k - 1].count <= file.ranges[k].offset,
                        "ranges are sorted and never overlap");
        }
        require(sum == file.gaussians, "a file's count is its ranges'");
        total += sum;
    }
    require(total == level.gaussians, "a level's count is its files'");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto& folder = splat_fuzz::sandbox_dir();
    for (const char* chunk : {"0_0", "1_0"}) {
        std::filesystem::create_directories(folder / chunk);
        std::ofstream(folder / chunk / "meta.json") << "{}";
    }
    const auto path = folder / "lod-meta.json";
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    splat_lod::io::StreamedSog sog;
    try {
        sog = splat_lod::io::read_streamed_sog_meta(path);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, path.string());
        return 0;
    }
    require(!sog.levels.empty(), "a streamed SOG has a level");
    for (const auto& level : sog.levels) check_level(level);
    return 0;
}
