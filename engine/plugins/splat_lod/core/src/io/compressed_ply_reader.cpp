// PlayCanvas / SuperSplat compressed PLY. Gaussians come in chunks of 256; each chunk stores the
// bounds of its positions, log-scales and (optionally) colours, and each Gaussian four uint32:
//   packed_position  x:11 y:10 z:11 bits (x in the top bits), unorm within the chunk bounds
//   packed_rotation  top 2 bits: index (in w,x,y,z order) of the largest component, dropped and
//                    rebuilt as sqrt(1 - others²); then the other three in order, 10 bits each,
//                    as (component / sqrt(2) + 0.5) — the "smallest three" encoding
//   packed_scale     11/10/11 unorm within the chunk's log-scale bounds
//   packed_color     R:8 G:8 B:8 A:8 (R in the top bits); colour is 0.5 + C0·f_dc (lerped within
//                    the chunk colour bounds when present), A is the activated opacity
// and an optional "sh" element holds f_rest_* (INRIA naming) as uchar: (v + 0.5) / 256 mapped to
// [-4, 4), with 0 and 255 pinned to the ends.
#include <array>
#include <cmath>

#include "io_util.h"
#include "readers.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod::io {
namespace {

constexpr std::uint64_t kChunkSize = 256;

// The chunk element's columns, in this order; the six colour bounds are optional.
constexpr std::array<const char*, 18> kChunkNames = {"min_x",       "min_y",       "min_z",        // position bounds
                                                     "max_x",       "max_y",       "max_z",        //
                                                     "min_scale_x", "min_scale_y", "min_scale_z",  // log-scale bounds
                                                     "max_scale_x", "max_scale_y", "max_scale_z",  //
                                                     "min_r",       "min_g",       "min_b",        // colour bounds
                                                     "max_r",       "max_g",       "max_b"};

struct ChunkBounds {
    std::array<std::vector<float>, 18> columns;  // one per kChunkNames entry
    bool has_colour = false;
};

float unorm(std::uint32_t value, int bits) {
    const std::uint32_t max = (1u << bits) - 1u;
    return static_cast<float>(value & max) / static_cast<float>(max);
}

float lerp(float a, float b, float t) {
    return a * (1.0f - t) + b * t;
}

glm::vec3 unpack_11_10_11(std::uint32_t v) {
    return {unorm(v >> 21, 11), unorm(v >> 11, 10), unorm(v, 11)};
}

Rotation unpack_rotation(std::uint32_t v) {
    constexpr float kScale = 1.41421356237f;  // the three stored components span ±1/sqrt(2)
    const float a = (unorm(v >> 20, 10) - 0.5f) * kScale;
    const float b = (unorm(v >> 10, 10) - 0.5f) * kScale;
    const float c = (unorm(v, 10) - 0.5f) * kScale;
    const float m = std::sqrt(std::max(0.0f, 1.0f - (a * a + b * b + c * c)));
    switch (v >> 30) {
        case 0:
            return {m, a, b, c};
        case 1:
            return {a, m, b, c};
        case 2:
            return {a, b, m, c};
        default:
            return {a, b, c, m};
    }
}

float unpack_sh_byte(std::uint32_t v) {
    const float n = v == 0 ? 0.0f : v == 255 ? 1.0f : (static_cast<float>(v) + 0.5f) / 256.0f;
    return (n - 0.5f) * 8.0f;
}

ChunkBounds read_chunks(const PlyFile& ply, const PlyElement& chunk) {
    ChunkBounds bounds;
    bounds.has_colour = chunk.find("min_r") != nullptr;
    const std::size_t needed = bounds.has_colour ? 18 : 12;
    for (std::size_t i = 0; i < needed; ++i) {
        const PlyProperty* p = chunk.find(kChunkNames[i]);
        if (!p) fail_file(ply.name, std::string("chunk element has no property \"") + kChunkNames[i] + "\"");
        bounds.columns[i] = ply.column_f32(chunk, *p);
    }
    return bounds;
}

std::vector<std::uint32_t> packed(const PlyFile& ply, const PlyElement& vertex, const char* name) {
    const PlyProperty* p = vertex.find(name);
    if (!p) fail_file(ply.name, std::string("compressed PLY vertex element has no property \"") + name + "\"");
    return ply.column_u32(vertex, *p);
}

void decode_vertices(const PlyFile& ply, const PlyElement& vertex, const ChunkBounds& b, SplatCloud& cloud) {
    const auto positions = packed(ply, vertex, "packed_position");
    const auto rotations = packed(ply, vertex, "packed_rotation");
    const auto scales = packed(ply, vertex, "packed_scale");
    const auto colours = packed(ply, vertex, "packed_color");
    const auto& c = b.columns;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const std::size_t k = i / kChunkSize;
        const glm::vec3 p = unpack_11_10_11(positions[i]);
        cloud.positions[i] = {lerp(c[0][k], c[3][k], p.x), lerp(c[1][k], c[4][k], p.y), lerp(c[2][k], c[5][k], p.z)};
        const glm::vec3 s = unpack_11_10_11(scales[i]);
        cloud.log_scales[i] = {lerp(c[6][k], c[9][k], s.x), lerp(c[7][k], c[10][k], s.y), lerp(c[8][k], c[11][k], s.z)};
        cloud.rotations[i] = unpack_rotation(rotations[i]);
        glm::vec3 rgb{unorm(colours[i] >> 24, 8), unorm(colours[i] >> 16, 8), unorm(colours[i] >> 8, 8)};
        if (b.has_colour)
            rgb = {lerp(c[12][k], c[15][k], rgb.x), lerp(c[13][k], c[16][k], rgb.y), lerp(c[14][k], c[17][k], rgb.z)};
        cloud.sh_dc[i] = (rgb - glm::vec3(0.5f)) / kShC0;
        cloud.opacity_logits[i] = unit_to_logit(unorm(colours[i], 8));
    }
}

int sh_degree_of(const PlyFile& ply, const PlyElement& sh) {
    for (int degree = 1; degree <= kMaxShDegree; ++degree)
        if (sh.properties.size() == static_cast<std::size_t>(3 * sh_rest_coeffs(degree))) return degree;
    fail_file(ply.name,
              "sh element has " + std::to_string(sh.properties.size()) + " properties: expected 9, 24 or 45 f_rest_*");
}

void decode_sh(const PlyFile& ply, const PlyElement& sh, SplatCloud& cloud) {
    if (sh.count != cloud.size())
        fail_file(ply.name, "sh element has " + std::to_string(sh.count) + " rows but vertex has " +
                                std::to_string(cloud.size()));
    cloud.set_sh_degree(sh_degree_of(ply, sh));
    const int coeffs = sh_rest_coeffs(cloud.sh_degree);
    for (int ch = 0; ch < 3; ++ch)
        for (int k = 0; k < coeffs; ++k) {
            const std::string name = "f_rest_" + std::to_string(ch * coeffs + k);
            const PlyProperty* p = sh.find(name);
            if (!p) fail_file(ply.name, "sh element has no property \"" + name + "\"");
            const auto bytes = ply.column_u32(sh, *p);
            for (std::size_t i = 0; i < cloud.size(); ++i)
                cloud.sh_rest_at(i, k + 1, ch) = unpack_sh_byte(std::min<std::uint32_t>(bytes[i], 255));
        }
}

}  // namespace

bool is_compressed_ply(const PlyFile& ply) {
    const PlyElement* vertex = ply.find_element("vertex");
    return ply.find_element("chunk") && vertex && vertex->find("packed_position");
}

SplatCloud decode_compressed_ply(const PlyFile& ply, LoadReport& report) {
    const PlyElement& chunk = *ply.find_element("chunk");
    const PlyElement& vertex = *ply.find_element("vertex");
    report.format = "PlayCanvas compressed PLY";
    report.gaussians_in_file = static_cast<std::size_t>(vertex.count);
    const std::uint64_t chunks_needed = vertex.count / kChunkSize + (vertex.count % kChunkSize != 0 ? 1 : 0);
    if (chunk.count != chunks_needed)
        fail_file(ply.name, "chunk element has " + std::to_string(chunk.count) + " rows but " +
                                std::to_string(vertex.count) + " Gaussians need " + std::to_string(chunks_needed));
    for (const auto& e : ply.elements)
        if (e.name != "chunk" && e.name != "vertex" && e.name != "sh")
            report.warnings.push_back("element \"" + e.name + "\" ignored");
    const ChunkBounds bounds = read_chunks(ply, chunk);
    SplatCloud cloud;
    cloud.resize(static_cast<std::size_t>(vertex.count));
    decode_vertices(ply, vertex, bounds, cloud);
    if (const PlyElement* sh = ply.find_element("sh")) decode_sh(ply, *sh, cloud);
    return cloud;
}

}  // namespace splat_lod::io
