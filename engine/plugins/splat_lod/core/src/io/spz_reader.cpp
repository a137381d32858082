// Niantic SPZ. Two containers around the same per-attribute arrays:
//   v2/v3: gzip( 16-byte header | positions | alphas | colours | scales | rotations | sh )
//   v4:    32-byte header | [extensions] | table of contents at tocByteOffset: per stream
//          (u64 compressed size, u64 uncompressed size) | one zstd frame per stream, in the
//          same attribute order, back to back.
// Header: magic "NGSP" (0x5053474e LE), u32 version, u32 numPoints, u8 shDegree,
// u8 fractionalBits, u8 flags (1 = antialiased, 2 = has extensions), u8 reserved (v4: the number
// of streams), and in v4 u32 tocByteOffset + 12 reserved bytes.
// Arrays: positions 3×24-bit signed fixed point with fractionalBits; alpha u8 = sigmoid(opacity);
// colour u8 = f_dc·0.15·255 + 127.5; scale u8 = (log-scale + 10)·16; rotation v2: 3×u8 x,y,z as
// (q + 1)·127.5 with w ≥ 0 rebuilt, v3+: u32 "smallest three" (see unpack_smallest_three);
// SH u8 = coefficient·128 + 128, per Gaussian coefficient-major, channel-minor.
#include <algorithm>
#include <array>
#include <cmath>

#include "decompress.h"
#include "engine/core/file_io.h"
#include "io_util.h"
#include "readers.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod {
namespace {

constexpr std::uint32_t kMagic = 0x5053474e;
constexpr std::uint64_t kLegacyHeaderSize = 16;
constexpr std::uint64_t kV4HeaderSize = 32;
constexpr std::uint8_t kFlagAntialiased = 0x1;
constexpr std::uint8_t kFlagExtensions = 0x2;
// Room for extension records in a legacy stream; real ones are a few dozen bytes.
constexpr std::uint64_t kMaxLegacyExtensionBytes = 1 << 20;
constexpr float kColourScale = 0.15f;

struct SpzHeader {
    std::uint32_t version = 0;
    std::uint32_t num_points = 0;
    int sh_degree = 0;
    int fractional_bits = 0;
    std::uint8_t flags = 0;
};

// Bytes per Gaussian of each array, in file order.
struct ArraySizes {
    std::array<std::uint64_t, 6> per_point{};
    std::uint64_t total_per_point() const {
        std::uint64_t sum = 0;
        for (auto s : per_point) sum += s;
        return sum;
    }
};

ArraySizes array_sizes(const SpzHeader& h) {
    const std::uint64_t rotation = h.version >= 3 ? 4 : 3;
    const auto sh = static_cast<std::uint64_t>(3 * sh_rest_coeffs(h.sh_degree));
    return {{9, 1, 3, 3, rotation, sh}};
}

SpzHeader parse_header(std::span<const std::uint8_t> bytes, const std::string& name) {
    const auto head = io::slice(bytes, 0, kLegacyHeaderSize, name, "SPZ header");
    if (io::load_u32le(head.data()) != kMagic) io::fail_at(name, 0, "not an SPZ file (no NGSP magic)");
    SpzHeader h;
    h.version = io::load_u32le(head.data() + 4);
    h.num_points = io::load_u32le(head.data() + 8);
    h.sh_degree = head[12];
    h.fractional_bits = head[13];
    h.flags = head[14];
    if (h.version == 1) io::fail_at(name, 4, "SPZ version 1 (float16 positions) is not supported");
    if (h.version < 1 || h.version > 4) io::fail_at(name, 4, "unknown SPZ version " + std::to_string(h.version));
    if (h.sh_degree > kMaxShDegree)
        io::fail_at(name, 12, "SH degree " + std::to_string(h.sh_degree) + " is not supported (0..3)");
    return h;
}

// x, y, z, w in SPZ order from the 2-bit index of the largest component and three 10-bit fields
// (sign bit + 9-bit magnitude of |q_i|·sqrt(2)), the first remaining component in the highest bits.
Rotation unpack_smallest_three(std::uint32_t packed) {
    constexpr float kInvSqrt2 = 0.70710678118f;
    float q[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const unsigned largest = packed >> 30;
    float sum = 0.0f;
    for (int i = 3; i >= 0; --i) {
        if (static_cast<unsigned>(i) == largest) continue;
        const float magnitude = kInvSqrt2 * static_cast<float>(packed & 511u) / 511.0f;
        q[i] = (packed >> 9) & 1u ? -magnitude : magnitude;
        sum += q[i] * q[i];
        packed >>= 10;
    }
    q[largest] = std::sqrt(std::max(0.0f, 1.0f - sum));
    return {q[3], q[0], q[1], q[2]};
}

Rotation unpack_first_three(const std::uint8_t* p) {
    const float x = static_cast<float>(p[0]) / 127.5f - 1.0f;
    const float y = static_cast<float>(p[1]) / 127.5f - 1.0f;
    const float z = static_cast<float>(p[2]) / 127.5f - 1.0f;
    return {std::sqrt(std::max(0.0f, 1.0f - (x * x + y * y + z * z))), x, y, z};
}

float fixed24(const std::uint8_t* p, int fractional_bits) {
    std::int32_t v = static_cast<std::int32_t>(p[0] | p[1] << 8 | p[2] << 16);
    if (v & 0x800000) v -= 0x1000000;  // sign-extend 24 bits
    return std::ldexp(static_cast<float>(v), -fractional_bits);
}

// arrays[k] holds array k of ArraySizes for every Gaussian.
SplatCloud decode_arrays(const SpzHeader& h, const std::array<std::span<const std::uint8_t>, 6>& arrays) {
    SplatCloud cloud;
    cloud.sh_degree = h.sh_degree;
    cloud.resize(h.num_points);
    const std::size_t stride = cloud.sh_rest_stride();
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const std::uint8_t* p = arrays[0].data() + 9 * i;
        cloud.positions[i] = {fixed24(p, h.fractional_bits), fixed24(p + 3, h.fractional_bits),
                              fixed24(p + 6, h.fractional_bits)};
        cloud.opacity_logits[i] = io::unit_to_logit(static_cast<float>(arrays[1][i]) / 255.0f);
        const std::uint8_t* c = arrays[2].data() + 3 * i;
        const std::uint8_t* s = arrays[3].data() + 3 * i;
        for (int k = 0; k < 3; ++k) {
            cloud.sh_dc[i][k] = (static_cast<float>(c[k]) / 255.0f - 0.5f) / kColourScale;
            cloud.log_scales[i][k] = static_cast<float>(s[k]) / 16.0f - 10.0f;
        }
        cloud.rotations[i] = h.version >= 3 ? unpack_smallest_three(io::load_u32le(arrays[4].data() + 4 * i))
                                            : unpack_first_three(arrays[4].data() + 3 * i);
        const std::uint8_t* sh = arrays[5].data() + stride * i;
        for (std::size_t k = 0; k < stride; ++k)
            cloud.sh_rest[stride * i + k] = (static_cast<float>(sh[k]) - 128.0f) / 128.0f;
    }
    return cloud;
}

// v2/v3 payload (already decompressed, or stored raw): header, optional extensions, arrays.
SplatCloud decode_legacy(std::span<const std::uint8_t> payload, const std::string& name, LoadReport& report) {
    const SpzHeader h = parse_header(payload, name);
    if (h.version > 3) io::fail_at(name, 4, "SPZ version 4 inside a gzip stream");
    const ArraySizes sizes = array_sizes(h);
    const std::uint64_t data_size = io::checked_mul(h.num_points, sizes.total_per_point(), name, "SPZ arrays");
    const std::uint64_t available = payload.size() - kLegacyHeaderSize;
    if (available < data_size)
        io::fail_at(name, payload.size(),
                    "SPZ data end after " + std::to_string(payload.size()) + " decompressed bytes; " +
                        std::to_string(h.num_points) + " Gaussians need " +
                        std::to_string(kLegacyHeaderSize + data_size) + " (truncated)");
    // The reference writer puts extension records between the header and the arrays.
    std::uint64_t offset = kLegacyHeaderSize;
    if (available > data_size) {
        const std::uint64_t extra = available - data_size;
        if (h.flags & kFlagExtensions) {
            offset += extra;
            report.warnings.push_back(std::to_string(extra) + " bytes of SPZ extensions skipped");
        } else {
            report.warnings.push_back(std::to_string(extra) + " bytes after the SPZ arrays ignored");
        }
    }
    std::array<std::span<const std::uint8_t>, 6> arrays;
    for (std::size_t k = 0; k < arrays.size(); ++k) {
        const std::uint64_t size = sizes.per_point[k] * h.num_points;
        arrays[k] = io::slice(payload, offset, size, name, "SPZ array");
        offset += size;
    }
    report.format = "SPZ v" + std::to_string(h.version);
    report.gaussians_in_file = h.num_points;
    report.antialiased = (h.flags & kFlagAntialiased) != 0;
    return decode_arrays(h, arrays);
}

SplatCloud read_gzip_spz(std::span<const std::uint8_t> bytes, const std::string& name, LoadReport& report) {
    // Peek at the header to learn how large the payload may be, then inflate up to that bound.
    const auto head = io::gunzip(bytes, kLegacyHeaderSize, true, name);
    if (head.size() < kLegacyHeaderSize) io::fail_file(name, "gzip stream holds no complete SPZ header");
    const SpzHeader h = parse_header(head, name);
    const std::uint64_t data_size = io::checked_mul(h.num_points, array_sizes(h).total_per_point(), name, "SPZ arrays");
    const std::uint64_t limit =
        io::checked_add(kLegacyHeaderSize + kMaxLegacyExtensionBytes, data_size, name, "SPZ payload");
    const auto payload = io::gunzip(bytes, limit, false, name);
    SplatCloud cloud = decode_legacy(payload, name, report);
    report.format += " (gzip)";
    return cloud;
}

SplatCloud read_v4(std::span<const std::uint8_t> bytes, const std::string& name, LoadReport& report) {
    const SpzHeader h = parse_header(bytes, name);
    const auto head = io::slice(bytes, 0, kV4HeaderSize, name, "SPZ v4 header");
    const ArraySizes sizes = array_sizes(h);
    const std::size_t streams = h.sh_degree > 0 ? 6 : 5;
    if (head[15] != streams)
        io::fail_at(name, 15,
                    "SPZ v4 declares " + std::to_string(head[15]) + " streams, expected " + std::to_string(streams) +
                        " for SH degree " + std::to_string(h.sh_degree));
    const std::uint64_t toc = io::load_u32le(head.data() + 16);
    if (toc < kV4HeaderSize) io::fail_at(name, 16, "SPZ v4 table of contents offset " + std::to_string(toc) + " < 32");
    if (toc > kV4HeaderSize && (h.flags & kFlagExtensions))
        report.warnings.push_back(std::to_string(toc - kV4HeaderSize) + " bytes of SPZ extensions skipped");
    const auto entries = io::slice(bytes, toc, 16 * streams, name, "SPZ v4 table of contents");
    std::uint64_t offset = toc + 16 * streams;
    std::vector<std::vector<std::uint8_t>> decoded(6);
    for (std::size_t k = 0; k < streams; ++k) {
        const std::uint64_t compressed = io::load_u64le(entries.data() + 16 * k);
        const std::uint64_t uncompressed = io::load_u64le(entries.data() + 16 * k + 8);
        const std::uint64_t expected = io::checked_mul(sizes.per_point[k], h.num_points, name, "SPZ stream");
        if (uncompressed != expected)
            io::fail_at(name, toc + 16 * k + 8,
                        "stream " + std::to_string(k) + " claims " + std::to_string(uncompressed) + " bytes, " +
                            std::to_string(h.num_points) + " Gaussians need " + std::to_string(expected));
        const auto frame = io::slice(bytes, offset, compressed, name, "zstd stream " + std::to_string(k));
        if (expected > 0 || compressed > 0) decoded[k] = io::unzstd(frame, expected, offset, name);
        offset += compressed;
    }
    if (offset < bytes.size())
        report.warnings.push_back(std::to_string(bytes.size() - offset) + " bytes after the last stream ignored");
    std::array<std::span<const std::uint8_t>, 6> arrays;
    for (std::size_t k = 0; k < arrays.size(); ++k) arrays[k] = decoded[k];
    report.format = "SPZ v4 (zstd)";
    report.gaussians_in_file = h.num_points;
    report.antialiased = (h.flags & kFlagAntialiased) != 0;
    return decode_arrays(h, arrays);
}

bool is_gzip(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b;
}

}  // namespace

SplatCloud read_spz(std::span<const std::uint8_t> bytes, const std::string& name, LoadReport* report) {
    LoadReport local;
    SplatCloud cloud;
    if (is_gzip(bytes)) {
        cloud = read_gzip_spz(bytes, name, local);
    } else {
        // Unwrapped NGSP data: v4 always, or a v2/v3 payload someone stored without gzip.
        const SpzHeader h = parse_header(bytes, name);
        cloud = h.version == 4 ? read_v4(bytes, name, local) : decode_legacy(bytes, name, local);
    }
    io::finish_load(cloud, local, report, name);
    return cloud;
}

SplatCloud read_spz(const std::filesystem::path& path, LoadReport* report) {
    const auto bytes = engine::read_binary_file(path);
    return read_spz(bytes, path.string(), report);
}

}  // namespace splat_lod
