// Niantic SPZ through read_spz: gzip v2/v3, bare v2/v3 payloads and zstd v4 (table of contents,
// one frame per stream). Contract (splat_lod/core/splat_io.h): a sanitised cloud or engine::Error naming
// the file; decompression never produces more than the header allows (io/decompress.h).
#include "splat_fuzz_support.h"
#include "splat_lod/core/splat_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return splat_fuzz::fuzz_splat_reader(data, size, "fuzz.spz", [](auto bytes, const std::string& name, auto* report) {
        return splat_lod::read_spz(bytes, name, report);
    });
}
