// glTF with KHR_gaussian_splatting through read_gltf_splats from bytes (.glb when the input starts with
// glTF, else JSON; no external files). Contract (splat_lod/core/splat_io.h): a sanitised cloud or
// engine::Error naming the file; accessors are bounds-checked against their buffers, node matrices
// that shear or collapse are refused.
#include "splat_fuzz_support.h"
#include "splat_lod/core/splat_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return splat_fuzz::fuzz_splat_reader(data, size, "fuzz.gltf",
                                         [](auto bytes, const std::string& name, auto* report) {
                                             return splat_lod::read_gltf_splats(bytes, name, report);
                                         });
}
