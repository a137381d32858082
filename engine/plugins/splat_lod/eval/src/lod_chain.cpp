#include "splat_lod/eval/lod_chain.h"

#include "splat_lod/core/streamed_sog.h"
#include "splat_lod/eval/eval_scene.h"

namespace splat_lod::eval {

std::string chain_method_name(int level) {
    return "chain_L" + std::to_string(level);
}

LodChain read_lod_chain(const std::filesystem::path& path) {
    const io::StreamedSog sog = io::read_streamed_sog_meta(path);
    LodChain chain;
    chain.meta = sog.meta;
    for (std::size_t level = 0; level < sog.levels.size(); ++level) {
        const io::StreamedSogLevel& described = io::streamed_sog_level(sog, static_cast<int>(level));
        LodChainLevel out;
        out.level = described.level;
        out.source = sog.meta.string() + "#" + std::to_string(level);
        for (const io::StreamedSogFile& file : described.files) out.files.push_back(file.file);
        out.gaussians = described.gaussians;
        chain.levels.push_back(std::move(out));
    }
    return chain;
}

std::vector<ComparisonScene> chain_comparisons(const LodChain& chain, const std::filesystem::path& main_file,
                                               std::shared_ptr<const SplatCloud> main_cloud) {
    std::vector<ComparisonScene> out;
    for (const LodChainLevel& level : chain.levels) {
        std::error_code ec;
        // The main scene's file serves a level that is that whole file (one file, every Gaussian).
        const bool is_main = main_cloud && level.files.size() == 1 &&
                             std::filesystem::equivalent(level.files[0], main_file, ec) &&
                             level.gaussians == main_cloud->size();
        const std::string where = level.files.size() == 1
                                      ? level.files[0].lexically_relative(chain.meta.parent_path()).string()
                                      : std::to_string(level.files.size()) + " chunk files";
        ComparisonScene comparison;
        comparison.method = chain_method_name(level.level);
        comparison.description = "level " + std::to_string(level.level) + " of " + chain.meta.filename().string() +
                                 " (" + where + ", " + std::to_string(level.gaussians) +
                                 " Gaussians) with the baseline renderer";
        comparison.load = [source = level.source, file = level.files.front(),
                           cloud = is_main ? main_cloud : nullptr]() {
            return cloud ? make_splat_scene(cloud, file) : load_splat_file_scene(source);
        };
        out.push_back(std::move(comparison));
    }
    return out;
}

}  // namespace splat_lod::eval
