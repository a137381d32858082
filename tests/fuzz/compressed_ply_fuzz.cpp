// PlayCanvas compressed PLY (chunk + packed vertex + optional sh element) through read_ply. The
// same entry point as inria_ply, with compressed seeds, so mutations exercise decode_compressed_ply.
// Input: the bytes of a PLY file. Contract (splat_lod/splat_io.h): read_ply either returns a
// sanitised cloud or throws engine::Error naming the file; it never crashes, hangs or allocates
// beyond what the input's size justifies.
#include "engine/core/error.h"
#include "fuzz_support.h"
#include "splat_lod/splat_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string name = "fuzz.compressed.ply";
    splat_lod::LoadReport report;
    splat_lod::SplatCloud cloud;
    try {
        cloud = splat_lod::read_ply(splat_fuzz::bytes_of(data, size), name, &report);
    } catch (const engine::Error& e) {
        splat_fuzz::check_error_names(e, name);
        return 0;
    }
    splat_fuzz::check_cloud(cloud, report);
    return 0;
}
