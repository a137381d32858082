// PlayCanvas compressed PLY (chunk + packed vertex + optional sh element) through read_ply. The
// same entry point as inria_ply, with compressed seeds, so mutations exercise decode_compressed_ply.
// Input: the bytes of a PLY file. Contract (splat_lod/core/splat_io.h): read_ply either returns a
// sanitised cloud or throws engine::Error naming the file; it never crashes, hangs or allocates
// beyond what the input's size justifies.
#include "splat_fuzz_support.h"
#include "splat_lod/core/splat_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return splat_fuzz::fuzz_splat_reader(
        data, size, "fuzz.compressed.ply",
        [](auto bytes, const std::string& name, auto* report) { return splat_lod::read_ply(bytes, name, report); });
}
