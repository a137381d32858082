// Format detection and the load_splat_file entry point; the SPZ axis conversion.
#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>

#include "io_util.h"
#include "splat_lod/core/capture_source.h"
#include "splat_lod/core/compact_chunk.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/streamed_sog.h"

namespace splat_lod {
namespace {

namespace fs = std::filesystem;

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

// The first bytes of the file, fewer if it is shorter.
std::vector<std::uint8_t> file_prefix(const fs::path& path, std::size_t size) {
    std::ifstream in(path, std::ios::binary);
    if (!in) io::fail_file(path.string(), "cannot open");
    std::vector<std::uint8_t> bytes(size);
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
    return bytes;
}

bool starts_with(const std::vector<std::uint8_t>& bytes, std::initializer_list<std::uint8_t> magic) {
    return bytes.size() >= magic.size() && std::equal(magic.begin(), magic.end(), bytes.begin());
}

}  // namespace

SplatFileFormat detect_splat_format(const fs::path& path) {
    std::error_code ec;
    int level = -1;
    const fs::path file = capture_file_and_level(path, &level);
    if (level >= 0 || io::is_streamed_sog(file)) return SplatFileFormat::streamed_sog;
    if (is_multi_part_capture(path)) return SplatFileFormat::tiles;
    if (fs::is_directory(path, ec)) return SplatFileFormat::sog;
    if (!fs::exists(path, ec)) io::fail_file(path.string(), "no such file or folder");
    const auto head = file_prefix(path, 8);
    if (starts_with(head, {'p', 'l', 'y', '\n'}) || starts_with(head, {'p', 'l', 'y', '\r'}))
        return SplatFileFormat::ply;
    if (starts_with(head, {0x1f, 0x8b}) || starts_with(head, {'N', 'G', 'S', 'P'})) return SplatFileFormat::spz;
    if (starts_with(head, {'g', 'l', 'T', 'F'})) return SplatFileFormat::gltf;
    if (starts_with(head, {'S', 'P', 'L', 'A', 'T', 'C', 'Z', '1'})) return SplatFileFormat::compact_chunk;
    const std::string ext = lower_extension(path);
    if (ext == ".ply") return SplatFileFormat::ply;
    if (ext == ".spz") return SplatFileFormat::spz;
    if (ext == ".splat") return SplatFileFormat::antimatter_splat;
    if (ext == ".gltf" || ext == ".glb") return SplatFileFormat::gltf;
    if (ext == ".json") return SplatFileFormat::sog;
    if (ext == ".sog") io::fail_file(path.string(), "zipped SOG bundles are not supported: unzip to a folder first");
    io::fail_file(path.string(), "unrecognised splat file (not PLY, SPZ, SOG, .splat, glTF or a world chunk)");
}

SplatCloud load_splat_file(const fs::path& path, LoadReport* report) {
    switch (detect_splat_format(path)) {
        case SplatFileFormat::ply:
            return read_ply(path, report);
        case SplatFileFormat::antimatter_splat:
            return read_antimatter_splat(path, report);
        case SplatFileFormat::spz:
            return read_spz(path, report);
        case SplatFileFormat::sog:
            return read_sog(path, report);
        case SplatFileFormat::gltf:
            return read_gltf_splats(path, report);
        case SplatFileFormat::streamed_sog:
        case SplatFileFormat::tiles:
            return read_capture(path, report);
        case SplatFileFormat::compact_chunk:
            return world::read_compact_chunk_file(path, report);
    }
    io::fail_file(path.string(), "unrecognised splat file");
}

float sh_sign_under_yz_flip(int coeff) {
    // Real SH basis in 3DGS order; a coefficient flips when its polynomial has odd total degree
    // in y and z: band 1: y, z, x; band 2: xy, yz, 3z²-1, xz, x²-y²;
    // band 3: y(3x²-y²), xyz, y(5z²-1), z(5z²-3), x(5z²-1), z(x²-y²), x(x²-3y²).
    static constexpr std::array<float, 16> kSigns = {1, -1, -1, 1, -1, 1, 1, -1, 1, -1, 1, -1, -1, 1, -1, 1};
    if (coeff < 1 || coeff > 15)
        engine::fail("splat_lod::sh_sign_under_yz_flip(): coefficient " + std::to_string(coeff));
    return kSigns[static_cast<std::size_t>(coeff)];
}

void convert_spz_axes_to_ply(SplatCloud& cloud) {
    cloud.check_consistent();
    const int coeffs = sh_rest_coeffs(cloud.sh_degree);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        cloud.positions[i].y = -cloud.positions[i].y;
        cloud.positions[i].z = -cloud.positions[i].z;
        // R' = M R M with M = diag(1,-1,-1), a rotation by pi about x: q' = (w, x, -y, -z).
        cloud.rotations[i].y = -cloud.rotations[i].y;
        cloud.rotations[i].z = -cloud.rotations[i].z;
        for (int k = 1; k <= coeffs; ++k) {
            const float sign = sh_sign_under_yz_flip(k);
            for (int c = 0; c < 3; ++c) cloud.sh_rest_at(i, k, c) *= sign;
        }
    }
}

}  // namespace splat_lod
