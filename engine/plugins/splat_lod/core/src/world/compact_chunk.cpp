// Compressed chunk files (compact_chunk.h): the header and one block's encoding and decoding.
#include "splat_lod/core/compact_chunk.h"

#include <zstd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>

#include "engine/core/error.h"
#include "splat_lod/core/compact_gaussians.h"
#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {
namespace {

constexpr std::array<char, 8> kMagic{'S', 'P', 'L', 'A', 'T', 'C', 'Z', '1'};
constexpr std::size_t kPageFloats = 19;

[[noreturn]] void fail(const std::string& name, const std::string& message) {
    engine::fail(name + ": " + message);
}

template <typename T>
void put(std::vector<std::uint8_t>& out, T value) {
    std::array<std::uint8_t, sizeof(T)> bytes{};
    std::memcpy(bytes.data(), &value, sizeof(T));
    out.insert(out.end(), bytes.begin(), bytes.end());
}

template <typename T>
T get(std::span<const std::uint8_t> bytes, std::size_t at) {
    T value{};
    std::memcpy(&value, bytes.data() + at, sizeof(T));
    return value;
}

std::array<float, kPageFloats> page_floats(const CompactPage& p) {
    return {p.position_lo.x,   p.position_lo.y, p.position_lo.z,  p.position_step.x, p.position_step.y,
            p.position_step.z, p.log_scale_lo,  p.log_scale_step, p.colour_lo.x,     p.colour_lo.y,
            p.colour_lo.z,     p.colour_step.x, p.colour_step.y,  p.colour_step.z,   p.coverage_lo,
            p.coverage_step,   p.sh_max.x,      p.sh_max.y,       p.sh_max.z};
}

CompactPage page_of(const std::array<float, kPageFloats>& f) {
    CompactPage p;
    p.position_lo = {f[0], f[1], f[2]};
    p.position_step = {f[3], f[4], f[5]};
    p.log_scale_lo = f[6];
    p.log_scale_step = f[7];
    p.colour_lo = {f[8], f[9], f[10]};
    p.colour_step = {f[11], f[12], f[13]};
    p.coverage_lo = f[14];
    p.coverage_step = f[15];
    p.sh_max = {f[16], f[17], f[18]};  // version 1: the bands' steps
    return p;
}

// A field of the record as the file stores it (compact_chunk.h: planes): `bits` bits at `offset` of
// 32-bit word `word`, less the same field of the record before (`delta`, the positions: the bake keeps
// neighbours together) or less the field before it in the same record (`after_previous`:
// coverage_max after coverage_min), modulo 2^bits.
enum class Transform : std::uint8_t { none, delta, after_previous };
struct Field {
    std::uint32_t word, offset, bits;
    Transform transform = Transform::none;
};

// SH words per record: version 1 stored a byte per coefficient, four to a word.
std::uint32_t sh_words(int sh_degree, std::uint32_t version) {
    return version == 1 ? static_cast<std::uint32_t>((3 * sh_rest_coeffs(sh_degree) + 3) / 4)
                        : compact_sh_words(sh_degree);
}

// Version 1's higher SH bands: byte (k − 1)·3 + c of the words is coefficient k, channel c, as
// (byte − 128)·step with the band's step in the page's last three floats.
void decode_version1_sh(std::span<const std::uint32_t> words, const CompactPage& page, SplatCloud& out, std::size_t i) {
    for (int k = 1; k <= sh_rest_coeffs(out.sh_degree); ++k)
        for (int c = 0; c < 3; ++c) {
            const std::size_t byte = std::size_t(k - 1) * 3 + c;
            const auto q = static_cast<int>(words[byte / 4] >> (8 * (byte % 4)) & 0xffu);
            out.sh_rest_at(i, k, c) = float(q - 128) * page.sh_max[k < 4 ? 0 : (k < 9 ? 1 : 2)];
        }
}

std::vector<Field> fields(int sh_degree, std::uint32_t version) {
    std::vector<Field> out{{0, 0, 16, Transform::delta},
                           {0, 16, 16, Transform::delta},
                           {1, 0, 16, Transform::delta},
                           {1, 16, 8},
                           {1, 24, 8},
                           {2, 0, 8},
                           {2, 8, 8},
                           {2, 16, 8},
                           {2, 24, 8},
                           {3, 0, 8},
                           {3, 8, 8},
                           {3, 16, 8},
                           {3, 24, 8},
                           {4, 0, 8},
                           {4, 8, 2},
                           {4, 10, 11},
                           {4, 21, 11, Transform::after_previous}};
    for (std::uint32_t w = 0; w < sh_words(sh_degree, version); ++w)
        for (std::uint32_t b = 0; b < 4; ++b) out.push_back({static_cast<std::uint32_t>(kCompactWords) + w, 8 * b, 8});
    return out;
}

std::uint32_t mask(std::uint32_t bits) {
    return bits >= 32 ? ~0u : (1u << bits) - 1u;
}

// The field's value in record k of `words` (records of `stride` words), transformed.
std::uint32_t stored_value(const std::vector<std::uint32_t>& words, std::size_t stride, std::size_t k, const Field* f) {
    const auto value = [&](std::size_t r, const Field& g) {
        return words[r * stride + g.word] >> g.offset & mask(g.bits);
    };
    std::uint32_t v = value(k, *f);
    if (f->transform == Transform::delta && k > 0) v -= value(k - 1, *f);
    if (f->transform == Transform::after_previous) v -= value(k, f[-1]);
    return v & mask(f->bits);
}

// Finite ranges can still decode to an infinity (a huge lo plus a step, 2 to a large power), and three
// rotation components to more than a unit quaternion: what a writer never makes, checked on every
// record so that a reader's promises (finite values, unit quaternions) hold.
bool decoded_valid(const SplatCloud& cloud, std::size_t i) {
    const Rotation& r = cloud.rotations[i];
    const float norm = r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z;
    if (!(std::abs(norm - 1.0f) < 1e-3f)) return false;
    const auto finite = [](const glm::vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    if (!finite(cloud.positions[i]) || !finite(cloud.log_scales[i]) || !finite(cloud.sh_dc[i]) ||
        !std::isfinite(cloud.coverage_min[i]) || !std::isfinite(cloud.coverage_max[i]))
        return false;
    const std::span<const float> rest =
        std::span(cloud.sh_rest).subspan(i * cloud.sh_rest_stride(), cloud.sh_rest_stride());
    return std::all_of(rest.begin(), rest.end(), [](float v) { return std::isfinite(v); });
}

// One plane's zstd frame into `out` (its size the block's record count): exactly one frame that
// expands to exactly that many bytes, or an error naming the file.
void unpack_plane(ZSTD_DCtx* context, std::span<const std::uint8_t> frame, std::vector<std::uint8_t>& out,
                  const std::string& name) {
    const std::size_t frame_bytes = ZSTD_findFrameCompressedSize(frame.data(), frame.size());
    if (ZSTD_isError(frame_bytes) || frame_bytes != frame.size())
        fail(name, "a plane is not one zstd frame (" +
                       std::string(ZSTD_isError(frame_bytes) ? ZSTD_getErrorName(frame_bytes) : "bytes after it") +
                       ")");
    if (ZSTD_getFrameContentSize(frame.data(), frame.size()) != out.size())
        fail(name, "a plane's zstd frame does not say it holds the block's " + std::to_string(out.size()) + " bytes");
    const std::size_t size = ZSTD_decompressDCtx(context, out.data(), out.size(), frame.data(), frame.size());
    if (ZSTD_isError(size) || size != out.size())
        fail(name, "a plane's zstd frame is corrupt (" +
                       std::string(ZSTD_isError(size) ? ZSTD_getErrorName(size) : "too short") + ")");
}

}  // namespace

std::vector<std::uint8_t> encode_compact_chunk_header(const CompactChunkHeader& header) {
    std::vector<std::uint8_t> out(kMagic.begin(), kMagic.end());
    put<std::uint32_t>(out, kCompactChunkVersion);
    put<std::uint32_t>(out, static_cast<std::uint32_t>(header.sh_degree));
    put<std::uint64_t>(out, header.count);
    put<std::uint32_t>(out, static_cast<std::uint32_t>(kCompactBlockRecords));
    put<std::uint32_t>(out, static_cast<std::uint32_t>(header.block_bytes.size()));
    for (const std::uint64_t count : header.prefix_count) put<std::uint64_t>(out, count);
    for (const std::uint32_t size : header.block_bytes) put<std::uint32_t>(out, size);
    return out;
}

std::uint32_t compact_chunk_block_count(std::span<const std::uint8_t> fixed, const std::string& name) {
    if (fixed.size() < kCompactChunkFixedHeaderBytes)
        fail(name,
             "is shorter than a compressed chunk's " + std::to_string(kCompactChunkFixedHeaderBytes) + "-byte header");
    if (!std::equal(kMagic.begin(), kMagic.end(), fixed.begin()))
        fail(name, "is not a compressed chunk file (its first bytes are not \"SPLATCZ1\")");
    const auto version = get<std::uint32_t>(fixed, 8);
    if (version < 1 || version > kCompactChunkVersion)
        fail(name, "compressed chunk format version " + std::to_string(version) +
                       " is not supported (this reads 1 to " + std::to_string(kCompactChunkVersion) + ")");
    return get<std::uint32_t>(fixed, 28);
}

CompactChunkHeader parse_compact_chunk_header(std::span<const std::uint8_t> bytes, const std::string& name) {
    const std::uint32_t blocks = compact_chunk_block_count(bytes, name);
    CompactChunkHeader header;
    header.version = get<std::uint32_t>(bytes, 8);
    header.sh_degree = static_cast<int>(get<std::uint32_t>(bytes, 12));
    header.count = get<std::uint64_t>(bytes, 16);
    if (get<std::uint32_t>(bytes, 12) > static_cast<std::uint32_t>(kMaxShDegree))
        fail(name, "header gives SH degree " + std::to_string(get<std::uint32_t>(bytes, 12)) + ", at most 3");
    if (get<std::uint32_t>(bytes, 24) != kCompactBlockRecords)
        fail(name, "header gives " + std::to_string(get<std::uint32_t>(bytes, 24)) + " records per block, expected " +
                       std::to_string(kCompactBlockRecords));
    for (std::size_t l = 0; l < header.prefix_count.size(); ++l)
        header.prefix_count[l] = get<std::uint64_t>(bytes, 32 + 8 * l);
    if (header.prefix_count[0] != header.count ||
        !std::is_sorted(header.prefix_count.rbegin(), header.prefix_count.rend()))
        fail(name, "header's prefix counts do not fall from its " + std::to_string(header.count) + " Gaussians");
    if (bytes.size() != kCompactChunkFixedHeaderBytes + 4ull * blocks)
        fail(name, "header of " + std::to_string(bytes.size()) + " bytes does not hold the table of its " +
                       std::to_string(blocks) + " blocks");
    header.block_bytes.resize(blocks);
    for (std::uint32_t b = 0; b < blocks; ++b)
        header.block_bytes[b] = get<std::uint32_t>(bytes, kCompactChunkFixedHeaderBytes + 4 * std::size_t{b});
    return header;
}

std::vector<std::uint8_t> encode_compact_chunk_block(const SplatCloud& cloud, std::size_t first, std::size_t count) {
    const int degree = cloud.sh_degree;
    for (std::size_t i = first; i < first + count; ++i)
        if (!gaussian_is_drawable(cloud, i))
            engine::fail("splat_lod::world::encode_compact_chunk_block(): Gaussian " + std::to_string(i) +
                         " has a non-finite value or a zero rotation");
    const CompactPage page = fit_compact_page(cloud, first, count, degree);
    const std::size_t stride = kCompactWords + compact_sh_words(degree);
    std::vector<std::uint32_t> words(stride * count);
    for (std::size_t k = 0; k < count; ++k) {
        const CompactRecord record = encode_compact(cloud, first + k, page);
        std::copy(record.begin(), record.end(), words.begin() + static_cast<std::ptrdiff_t>(k * stride));
        encode_compact_sh(cloud, first + k, page, degree,
                          std::span(words).subspan(k * stride + kCompactWords, stride - kCompactWords));
    }
    std::vector<std::uint8_t> out;
    for (const float f : page_floats(page)) put<float>(out, f);
    std::vector<std::vector<std::uint8_t>> planes;
    const std::vector<Field> table = fields(degree, kCompactChunkVersion);
    const std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)> context(ZSTD_createCCtx(), &ZSTD_freeCCtx);
    if (!context) engine::fail("splat_lod::world::encode_compact_chunk_block(): cannot initialise zstd");
    for (const Field& f : table)
        for (std::uint32_t byte = 0; byte < f.bits; byte += 8) {
            std::vector<std::uint8_t> plane(count);
            for (std::size_t k = 0; k < count; ++k)
                plane[k] = static_cast<std::uint8_t>(stored_value(words, stride, k, &f) >> byte);
            std::vector<std::uint8_t> packed(ZSTD_compressBound(count));
            const std::size_t size = ZSTD_compressCCtx(context.get(), packed.data(), packed.size(), plane.data(),
                                                       plane.size(), kCompactChunkZstdLevel);
            if (ZSTD_isError(size))
                engine::fail(std::string("splat_lod::world::encode_compact_chunk_block(): zstd: ") +
                             ZSTD_getErrorName(size));
            packed.resize(size);
            put<std::uint32_t>(out, static_cast<std::uint32_t>(size));
            planes.push_back(std::move(packed));
        }
    for (const auto& plane : planes) out.insert(out.end(), plane.begin(), plane.end());
    return out;
}

void decode_compact_chunk_block(std::span<const std::uint8_t> block, std::size_t count,
                                const CompactChunkHeader& header, SplatCloud& out, std::size_t at,
                                const std::string& name) {
    const int sh_degree = header.sh_degree;
    const std::vector<Field> table = fields(sh_degree, header.version);
    std::size_t plane_count = 0;
    for (const Field& f : table) plane_count += (f.bits + 7) / 8;
    const std::size_t sizes_at = 4 * kPageFloats;
    if (block.size() < sizes_at + 4 * plane_count) fail(name, "a block is shorter than its plane table");
    std::array<float, kPageFloats> floats{};
    for (std::size_t f = 0; f < kPageFloats; ++f) {
        floats[f] = get<float>(block, 4 * f);
        if (!std::isfinite(floats[f])) fail(name, "a block's quantisation ranges are not finite");
    }
    const CompactPage page = page_of(floats);
    const std::size_t stride = kCompactWords + sh_words(sh_degree, header.version);
    std::vector<std::uint32_t> words(stride * count, 0u);
    std::size_t plane = 0, offset = sizes_at + 4 * plane_count;
    const std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(), &ZSTD_freeDCtx);
    if (!context) fail(name, "cannot initialise zstd");
    std::vector<std::uint8_t> bytes(count);
    for (const Field& f : table) {
        // The stored values, then the transform undone in record order.
        std::vector<std::uint32_t> values(count, 0u);
        for (std::uint32_t byte = 0; byte < f.bits; byte += 8, ++plane) {
            const std::uint64_t size = get<std::uint32_t>(block, sizes_at + 4 * plane);
            if (size > block.size() - offset) fail(name, "a block's plane " + std::to_string(plane) + " runs past it");
            unpack_plane(context.get(), block.subspan(offset, static_cast<std::size_t>(size)), bytes, name);
            for (std::size_t k = 0; k < count; ++k) values[k] |= std::uint32_t{bytes[k]} << byte;
            offset += size;
        }
        const Field* previous = &f - 1;
        for (std::size_t k = 0; k < count; ++k) {
            std::uint32_t v = values[k];
            if (f.transform == Transform::delta && k > 0) v += words[(k - 1) * stride + f.word] >> f.offset;
            if (f.transform == Transform::after_previous) v += words[k * stride + previous->word] >> previous->offset;
            words[k * stride + f.word] |= (v & mask(f.bits)) << f.offset;
        }
    }
    if (offset != block.size())
        fail(name, "a block has " + std::to_string(block.size() - offset) + " bytes after its planes");
    for (std::size_t k = 0; k < count; ++k) {
        CompactRecord record{};
        std::copy_n(words.begin() + static_cast<std::ptrdiff_t>(k * stride), kCompactWords, record.begin());
        const auto sh =
            std::span<const std::uint32_t>(words).subspan(k * stride + kCompactWords, stride - kCompactWords);
        decode_compact_into(record, sh, page, header.version == 1 ? 0 : sh_degree, out, at + k);
        if (header.version == 1) decode_version1_sh(sh, page, out, at + k);
        if (!decoded_valid(out, at + k))
            fail(name, "record " + std::to_string(k) +
                           " of a block decodes to values that are not finite or to a "
                           "rotation that is not a unit quaternion");
    }
}

}  // namespace splat_lod::world
