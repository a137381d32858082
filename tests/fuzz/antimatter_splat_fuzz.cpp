// antimatter15 .splat (32-byte records) through read_antimatter_splat.
// Contract (splat_lod/splat_io.h): a sanitised cloud or engine::Error naming the file.
#include "engine/core/error.h"
#include "fuzz_support.h"
#include "splat_lod/splat_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string name = "fuzz.splat";
    splat_lod::LoadReport report;
    splat_lod::SplatCloud cloud;
    try {
        cloud = splat_lod::read_antimatter_splat(splat_fuzz::bytes_of(data, size), name, &report);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, name);
        return 0;
    }
    splat_fuzz::check_cloud(cloud, report);
    return 0;
}
