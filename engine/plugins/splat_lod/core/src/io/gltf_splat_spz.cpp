// KHR_gaussian_splatting_compression_spz_2: an SPZ stream in a buffer view instead of the attributes.
#include <tiny_gltf.h>

#include <array>

#include "engine/core/error.h"
#include "gltf_splats.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod::io {
namespace {

// Sign of SH coefficient k (1..15) under (x, y, z) -> (-x, y, -z): the parity of its x, z degree.
// Band 1: y, z, x; band 2: xy, yz, 3z²-1, xz, x²-y²; band 3: y(3x²-y²), xyz, y(5z²-1), z(5z²-3),
// x(5z²-1), z(x²-y²), x(x²-3y²).
constexpr std::array<float, 16> kSignsUnderXzFlip = {1, 1, -1, -1, -1, -1, 1, 1, 1, 1, 1, 1, -1, -1, -1, -1};

// SPZ's right-up-back to glTF's left-up-front: a rotation by pi about y.
void convert_spz_axes_to_gltf(SplatCloud& cloud) {
    const int coeffs = sh_rest_coeffs(cloud.sh_degree);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        cloud.positions[i].x = -cloud.positions[i].x;
        cloud.positions[i].z = -cloud.positions[i].z;
        cloud.rotations[i].x = -cloud.rotations[i].x;  // R' = M R M, M = diag(-1, 1, -1): q' = (w, -x, y, -z)
        cloud.rotations[i].z = -cloud.rotations[i].z;
        for (int k = 1; k <= coeffs; ++k)
            for (int c = 0; c < 3; ++c) cloud.sh_rest_at(i, k, c) *= kSignsUnderXzFlip[static_cast<std::size_t>(k)];
    }
}

}  // namespace

SplatCloud decode_spz_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, int view,
                                const std::string& where, LoadReport& report) {
    const std::string what = where + ": " + kGltfSpzExtension;
    if (static_cast<std::size_t>(view) >= model.bufferViews.size()) engine::fail(what + ": bufferView out of range");
    const auto& v = model.bufferViews[static_cast<std::size_t>(view)];
    if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= model.buffers.size())
        engine::fail(what + ": buffer index out of range");
    const auto& data = model.buffers[static_cast<std::size_t>(v.buffer)].data;
    if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
        engine::fail(what + ": buffer view exceeds its buffer (truncated file?)");
    LoadReport spz;
    SplatCloud cloud = read_spz(std::span(data.data() + v.byteOffset, v.byteLength), what, &spz);
    report.dropped_non_finite += spz.dropped_non_finite;
    report.dropped_zero_rotation += spz.dropped_zero_rotation;
    report.antialiased = report.antialiased || spz.antialiased;
    for (const auto& warning : spz.warnings) report.warnings.push_back(warning);
    const auto position = primitive.attributes.find("POSITION");
    if (position != primitive.attributes.end() && position->second >= 0 &&
        static_cast<std::size_t>(position->second) < model.accessors.size()) {
        const std::size_t count = model.accessors[static_cast<std::size_t>(position->second)].count;
        if (count != spz.gaussians_in_file)
            engine::fail(what + ": POSITION has " + std::to_string(count) + " elements, the SPZ stream " +
                         std::to_string(spz.gaussians_in_file) + " Gaussians");
    }
    convert_spz_axes_to_gltf(cloud);
    return cloud;
}

}  // namespace splat_lod::io
