// Niantic SPZ through read_spz: gzip v2/v3, bare v2/v3 payloads and zstd v4 (table of contents,
// one frame per stream). Contract (splat_lod/splat_io.h): a sanitised cloud or engine::Error naming
// the file; decompression never produces more than the header allows (io/decompress.h).
#include "engine/core/error.h"
#include "fuzz_support.h"
#include "splat_lod/splat_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string name = "fuzz.spz";
    splat_lod::LoadReport report;
    splat_lod::SplatCloud cloud;
    try {
        cloud = splat_lod::read_spz(splat_fuzz::bytes_of(data, size), name, &report);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, name);
        return 0;
    }
    splat_fuzz::check_cloud(cloud, report);
    return 0;
}
