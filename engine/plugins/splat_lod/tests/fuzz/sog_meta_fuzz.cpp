// PlayCanvas SOG meta.json (v1 ranges, v2 codebooks) through parse_sog_meta (io/sog_meta.h).
// Contract: a validated SogMeta or engine::Error naming the file and the key; texture names are
// plain file names, so a hostile meta.json cannot point the reader at other files.
#include <cmath>

#include "engine/core/error.h"
#include "splat_fuzz_support.h"
#include "splat_lod/core/sog_meta.h"

namespace {

using splat_fuzz::require;

void check_file_name(const std::string& file) {
    require(!file.empty() && file != "." && file != ".." && file.find_first_of("/\\") == std::string::npos,
            "texture name \"" + file + "\" is a plain file name");
}

void check_quantiser(const splat_lod::io::SogQuantiser& q, int version) {
    if (version == 2) {
        require(q.codebook.size() == 256, "a v2 codebook has 256 entries");
        for (float v : q.codebook) require(std::isfinite(v), "codebook entries are finite");
    } else {
        require(q.codebook.empty() && std::isfinite(q.lo) && std::isfinite(q.hi), "a v1 range is finite");
    }
}

void check_meta(const splat_lod::io::SogMeta& meta) {
    require(meta.version == 1 || meta.version == 2, "version is 1 or 2");
    for (int k = 0; k < 3; ++k) {
        const auto axis = static_cast<std::size_t>(k);
        require(std::isfinite(meta.means_min[axis]) && std::isfinite(meta.means_max[axis]), "means bounds are finite");
        check_quantiser(meta.scales[axis], meta.version);
        check_quantiser(meta.colour[axis], meta.version);
    }
    require(meta.opacity_logit.has_value() == (meta.version == 1), "only v1 has an opacity logit range");
    if (meta.opacity_logit) check_quantiser(*meta.opacity_logit, 1);
    for (const auto* file :
         {&meta.means_lower_file, &meta.means_upper_file, &meta.scales_file, &meta.quats_file, &meta.sh0_file})
        check_file_name(*file);
    if (meta.sh_n) {
        check_quantiser(meta.sh_n->quantiser, meta.version);
        check_file_name(meta.sh_n->centroids_file);
        check_file_name(meta.sh_n->labels_file);
        if (meta.version == 2) require(meta.sh_n->bands >= 1 && meta.sh_n->bands <= 3, "shN bands are 1..3");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string name = "fuzz/meta.json";
    splat_lod::io::SogMeta meta;
    try {
        meta = splat_lod::io::parse_sog_meta(splat_fuzz::text_of(data, size), name);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, name);
        return 0;
    }
    check_meta(meta);
    return 0;
}
