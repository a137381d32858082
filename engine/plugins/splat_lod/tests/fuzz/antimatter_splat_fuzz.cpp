// antimatter15 .splat (32-byte records) through read_antimatter_splat.
// Contract (splat_lod/core/splat_io.h): a sanitised cloud or engine::Error naming the file.
#include "splat_fuzz_support.h"
#include "splat_lod/core/splat_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return splat_fuzz::fuzz_splat_reader(data, size, "fuzz.splat",
                                         [](auto bytes, const std::string& name, auto* report) {
                                             return splat_lod::read_antimatter_splat(bytes, name, report);
                                         });
}
