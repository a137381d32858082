// Seeds for the fuzz harnesses (README.md here and tests/fuzz/README.md), small enough to mutate fast:
//   fuzz_seed_maker --out DIR [--shared-data DIR]
// writes DIR/<harness>/<seed>: always the project-made binary seeds (the project's own writers,
// the unit tests' SPZ encoders, a compressed-PLY packer and PLY re-encodings here) and seeds cut
// down from the real files (a real header with the element counts cut and the data truncated to
// match, the first Gaussians of a real scene re-encoded, small real glTF/SOG files as they are):
// those kept in tests/data always, and with --shared-data also those only there. The committed
// seeds in seeds/ (here and in tests/fuzz) are the project-made ones plus hand-written text files.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>

#include <tiny_gltf.h>
#include <webp/encode.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_fuzz_support.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/chunk_writer.h"
#include "splat_lod/core/ply_file.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/stream_levels.h"
#include "splat_lod/worldgen/world_meshes.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
namespace io = splat_lod::io;
using Bytes = std::vector<std::uint8_t>;

struct SeedWriter {
    fs::path out;
    int written = 0;

    void operator()(const std::string& harness, const std::string& file, std::span<const std::uint8_t> bytes) {
        fs::create_directories(out / harness);
        splat_fuzz::write_file(out / harness / file, bytes);
        ++written;
    }
    void text(const std::string& harness, const std::string& file, const std::string& text) {
        (*this)(harness, file, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    }
};

// ---- PLY re-encoding: any PLY as columns, written back in another format or with fewer rows.

struct PlyColumn {
    std::string name;
    io::PlyType type;
    std::vector<double> values;
};
struct PlyTable {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyColumn> columns;
};

std::vector<PlyTable> tables_of(const Bytes& bytes) {
    const io::PlyFile ply = io::parse_ply(bytes, "seed");
    std::vector<PlyTable> tables;
    for (const auto& element : ply.elements) {
        PlyTable table{element.name, element.count, {}};
        for (const auto& p : element.properties) {
            const bool whole =
                p.type == io::PlyType::uint8 || p.type == io::PlyType::uint16 || p.type == io::PlyType::uint32;
            std::vector<double> values;
            if (whole)
                for (auto v : ply.column_u32(element, p)) values.push_back(v);
            else
                for (auto v : ply.column_f32(element, p)) values.push_back(v);
            table.columns.push_back({p.name, p.type, std::move(values)});
        }
        tables.push_back(std::move(table));
    }
    return tables;
}

void put_value(Bytes& out, io::PlyType type, double v, bool big_endian) {
    std::uint8_t raw[8];
    std::size_t size = io::ply_type_size(type);
    switch (type) {
        case io::PlyType::int8:
            raw[0] = static_cast<std::uint8_t>(static_cast<std::int8_t>(v));
            break;
        case io::PlyType::uint8:
            raw[0] = static_cast<std::uint8_t>(v);
            break;
        case io::PlyType::int16: {
            const auto x = static_cast<std::int16_t>(v);
            std::memcpy(raw, &x, 2);
            break;
        }
        case io::PlyType::uint16: {
            const auto x = static_cast<std::uint16_t>(v);
            std::memcpy(raw, &x, 2);
            break;
        }
        case io::PlyType::int32: {
            const auto x = static_cast<std::int32_t>(v);
            std::memcpy(raw, &x, 4);
            break;
        }
        case io::PlyType::uint32: {
            const auto x = static_cast<std::uint32_t>(v);
            std::memcpy(raw, &x, 4);
            break;
        }
        case io::PlyType::float32: {
            const auto x = static_cast<float>(v);
            std::memcpy(raw, &x, 4);
            break;
        }
        case io::PlyType::float64:
            std::memcpy(raw, &v, 8);
            break;
    }
    if (big_endian) std::reverse(raw, raw + size);
    out.insert(out.end(), raw, raw + size);
}

// `format`: "ascii", "binary_little_endian" or "binary_big_endian"; at most `max_rows[name]` rows
// per element (all when absent).
Bytes write_tables(const std::vector<PlyTable>& tables, const std::string& format,
                   const std::map<std::string, std::uint64_t>& max_rows = {}) {
    auto rows_of = [&](const PlyTable& t) {
        const auto it = max_rows.find(t.name);
        return it == max_rows.end() ? t.count : std::min(t.count, it->second);
    };
    std::ostringstream header;
    header << "ply\nformat " << format << " 1.0\ncomment fuzz seed (seed_maker.cpp)\n";
    for (const auto& t : tables) {
        header << "element " << t.name << " " << rows_of(t) << "\n";
        for (const auto& c : t.columns) header << "property " << io::ply_type_name(c.type) << " " << c.name << "\n";
    }
    header << "end_header\n";
    const std::string head = header.str();
    Bytes out(head.begin(), head.end());
    for (const auto& t : tables)
        for (std::uint64_t r = 0; r < rows_of(t); ++r) {
            std::string line;
            for (const auto& c : t.columns) {
                if (format != "ascii") {
                    put_value(out, c.type, c.values[r], format == "binary_big_endian");
                    continue;
                }
                char number[32];
                std::snprintf(number, sizeof number, "%.17g", c.values[r]);
                line += (line.empty() ? "" : " ") + std::string(number);
            }
            if (format != "ascii") continue;
            line += '\n';
            out.insert(out.end(), line.begin(), line.end());
        }
    return out;
}

// ---- PlayCanvas compressed PLY packer (the layout compressed_ply_reader.cpp decodes).

std::uint32_t unorm_bits(float t, int bits) {
    const float max = static_cast<float>((1u << bits) - 1u);
    return static_cast<std::uint32_t>(std::lround(std::clamp(t, 0.0f, 1.0f) * max));
}

float fraction(float v, float lo, float hi) {
    return hi > lo ? (v - lo) / (hi - lo) : 0.0f;
}

std::uint32_t pack_rotation(splat_lod::Rotation r) {
    float q[4] = {r.w, r.x, r.y, r.z};
    int largest = 0;
    for (int k = 1; k < 4; ++k)
        if (std::fabs(q[k]) > std::fabs(q[largest])) largest = k;
    const float sign = q[largest] < 0.0f ? -1.0f : 1.0f;
    std::uint32_t packed = static_cast<std::uint32_t>(largest);
    for (int k = 0; k < 4; ++k)
        if (k != largest) packed = packed << 10 | unorm_bits(sign * q[k] / 1.41421356f + 0.5f, 10);
    return packed;
}

std::vector<PlyTable> compressed_tables(const splat_lod::SplatCloud& cloud, bool colour_bounds) {
    const std::size_t n = cloud.size(), chunks = (n + 255) / 256;
    const char* names[] = {"min_x",       "min_y",       "min_z",       "max_x",       "max_y",       "max_z",
                           "min_scale_x", "min_scale_y", "min_scale_z", "max_scale_x", "max_scale_y", "max_scale_z",
                           "min_r",       "min_g",       "min_b",       "max_r",       "max_g",       "max_b"};
    PlyTable chunk{"chunk", chunks, {}}, vertex{"vertex", n, {}};
    for (int c = 0; c < (colour_bounds ? 18 : 12); ++c) chunk.columns.push_back({names[c], io::PlyType::float32, {}});
    for (const char* name : {"packed_position", "packed_rotation", "packed_scale", "packed_color"})
        vertex.columns.push_back({name, io::PlyType::uint32, {}});
    auto colour = [&](std::size_t i) { return glm::vec3(0.5f) + splat_lod::kShC0 * cloud.sh_dc[i]; };
    for (std::size_t k = 0; k < chunks; ++k) {
        const std::size_t begin = 256 * k, end = std::min(n, begin + 256);
        glm::vec3 lo[3] = {cloud.positions[begin], cloud.log_scales[begin], colour(begin)},
                  hi[3] = {lo[0], lo[1], lo[2]};
        for (std::size_t i = begin; i < end; ++i) {
            const glm::vec3 v[3] = {cloud.positions[i], cloud.log_scales[i], colour(i)};
            for (int a = 0; a < 3; ++a) lo[a] = glm::min(lo[a], v[a]), hi[a] = glm::max(hi[a], v[a]);
        }
        for (int c = 0; c < static_cast<int>(chunk.columns.size()); ++c)
            chunk.columns[static_cast<std::size_t>(c)].values.push_back(((c / 3) % 2 ? hi : lo)[c / 6][c % 3]);
        for (std::size_t i = begin; i < end; ++i) {
            std::uint32_t fields[2] = {0, 0};
            const glm::vec3 v[2] = {cloud.positions[i], cloud.log_scales[i]};
            for (int a = 0; a < 2; ++a)
                fields[a] = unorm_bits(fraction(v[a].x, lo[a].x, hi[a].x), 11) << 21 |
                            unorm_bits(fraction(v[a].y, lo[a].y, hi[a].y), 10) << 11 |
                            unorm_bits(fraction(v[a].z, lo[a].z, hi[a].z), 11);
            const glm::vec3 rgb = colour(i);
            std::uint32_t packed_colour = 0;
            for (int c = 0; c < 3; ++c) {
                const float t = colour_bounds ? fraction(rgb[c], lo[2][c], hi[2][c]) : rgb[c];
                packed_colour |= unorm_bits(t, 8) << (24 - 8 * c);
            }
            packed_colour |= unorm_bits(1.0f / (1.0f + std::exp(-cloud.opacity_logits[i])), 8);
            const double packed[4] = {static_cast<double>(fields[0]),
                                      static_cast<double>(pack_rotation(cloud.rotations[i])),
                                      static_cast<double>(fields[1]), static_cast<double>(packed_colour)};
            for (int c = 0; c < 4; ++c) vertex.columns[static_cast<std::size_t>(c)].values.push_back(packed[c]);
        }
    }
    std::vector<PlyTable> tables{chunk, vertex};
    if (cloud.sh_degree == 0) return tables;
    PlyTable sh{"sh", n, {}};
    const int coeffs = splat_lod::sh_rest_coeffs(cloud.sh_degree);
    for (int ch = 0; ch < 3; ++ch)
        for (int k = 0; k < coeffs; ++k) {
            PlyColumn column{"f_rest_" + std::to_string(ch * coeffs + k), io::PlyType::uint8, {}};
            for (std::size_t i = 0; i < n; ++i)
                column.values.push_back(unorm_bits(cloud.sh_rest_at(i, k + 1, ch) / 8.0f + 0.5f, 8));
            sh.columns.push_back(std::move(column));
        }
    tables.push_back(std::move(sh));
    return tables;
}

// ---- Seeds made by the project's own code.

void ply_seeds(SeedWriter& write) {
    using splat_io_test::make_cloud;
    write("inria_ply", "sh0.ply", splat_lod::encode_inria_ply(make_cloud(4, 0, 1)));
    write("inria_ply", "sh3_lod_extras.ply", splat_lod::encode_inria_ply(make_cloud(2, 3, 2, true, true)));
    const auto sh1 = tables_of(splat_lod::encode_inria_ply(make_cloud(3, 1, 3, true)));
    write("inria_ply", "sh1_lod_big_endian.ply", write_tables(sh1, "binary_big_endian"));
    write("inria_ply", "sh1_lod_ascii.ply", write_tables(sh1, "ascii"));
    // The reduced layout (no normals, no f_rest) with double positions and uchar levels.
    auto reduced = tables_of(splat_lod::encode_inria_ply(make_cloud(3, 0, 4)));
    auto& columns = reduced[0].columns;
    columns.erase(std::remove_if(columns.begin(), columns.end(), [](const PlyColumn& c) { return c.name[0] == 'n'; }),
                  columns.end());
    for (auto& c : columns)
        if (c.name.size() == 1) c.type = io::PlyType::float64;
    write("inria_ply", "reduced_double.ply", write_tables(reduced, "binary_little_endian"));

    write("compressed_ply", "300_sh1.compressed.ply",
          write_tables(compressed_tables(make_cloud(300, 1, 5), true), "binary_little_endian"));
    write("compressed_ply", "16_no_colour_bounds.compressed.ply",
          write_tables(compressed_tables(make_cloud(16, 0, 6), false), "binary_little_endian"));
    write("compressed_ply", "4_sh3_ascii.compressed.ply",
          write_tables(compressed_tables(make_cloud(4, 3, 7), true), "ascii"));
}

void splat_and_spz_seeds(SeedWriter& write) {
    using splat_io_test::encode_spz;
    using splat_io_test::make_cloud;
    write("antimatter_splat", "8.splat", splat_lod::encode_antimatter_splat(make_cloud(8, 0, 8)));
    write("antimatter_splat", "1.splat", splat_lod::encode_antimatter_splat(make_cloud(1, 0, 9)));
    write("spz", "v2_sh0.spz", encode_spz(make_cloud(5, 0, 10), 2));
    write("spz", "v3_sh1.spz", encode_spz(make_cloud(5, 1, 11), 3));
    write("spz", "v3_sh2_bare.spz", encode_spz(make_cloud(4, 2, 12), 3, false));
    write("spz", "v4_sh0.spz", encode_spz(make_cloud(6, 0, 13), 4));
    write("spz", "v4_sh3.spz", encode_spz(make_cloud(3, 3, 14), 4));
    write("gltf_splats", "4_sh0.glb", splat_lod::encode_gltf_splats(make_cloud(4, 0, 16), true));
    write("gltf_splats", "3_sh1.gltf", splat_lod::encode_gltf_splats(make_cloud(3, 1, 17), false));
    write("gltf_splats", "2_sh3_lod_extras.glb", splat_lod::encode_gltf_splats(make_cloud(2, 3, 18, true, true), true));
}

// Chunk files as the world generator writes them (INRIA PLY with LOD properties) behind the
// world_chunk harness's 7 control bytes: one of a few records, one of more than a checksum block.
void world_chunk_seeds(SeedWriter& write) {
    using splat_io_test::make_cloud;
    const auto seed = [&](const char* name, Bytes control, std::size_t n, int sh_degree) {
        const Bytes file = splat_lod::encode_inria_ply(make_cloud(n, sh_degree, 15, true));
        control.insert(control.end(), file.begin(), file.end());
        write("world_chunk", name, control);
    };
    seed("40_sh0.bin", {0, 200, 120, 40, 0, 255, 0}, 40, 0);
    seed("9_sh1_bad_block.bin", {2, 255, 128, 64, 30, 200, 0}, 9, 1);
    seed("1100_sh0_bad_second_block.bin", {2, 255, 255, 255, 3, 100, 1}, 1100, 0);
}

// Compressed chunk files as the world generator writes them: a few records, and more than one block
// over every stream level at SH degree 1.
void compact_chunk_seeds(SeedWriter& write, const std::filesystem::path& scratch) {
    using splat_io_test::make_cloud;
    const auto seed = [&](const char* name, std::size_t n, int sh_degree) {
        const splat_lod::world::StreamLevelRule rule;
        splat_lod::SplatCloud cloud = make_cloud(n, sh_degree, 15, true);
        cloud = cloud.permuted(splat_lod::world::stream_order(cloud, rule));
        splat_lod::world::write_chunk_file(cloud, scratch, "seed.splatc", {0, 0}, rule,
                                           splat_lod::world::ChunkCodec::compact);
        write("compact_chunk", name, engine::read_binary_file(scratch / "seed.splatc"));
        fs::remove(scratch / "seed.splatc");
    };
    seed("40_sh0.splatc", 40, 0);
    seed("1500_sh1.splatc", 1500, 1);
}

std::string codebook(float lo, float hi) {
    std::string text = "[";
    for (int i = 0; i < 256; ++i) {
        char number[24];
        std::snprintf(number, sizeof number, "%s%.5g", i ? ", " : "", lo + (hi - lo) * static_cast<float>(i) / 255.0f);
        text += number;
    }
    return text + "]";
}

void sog_seeds(SeedWriter& write) {
    const std::string means =
        R"("means": {"mins": [-2, -1.5, -3], "maxs": [2.5, 1, 3], "files": ["means_l.webp", "means_u.webp"]})";
    const std::string quats = R"("quats": {"files": ["quats.webp"]})";
    write.text("sog_meta", "v2_sh2.json",
               "{\"version\": 2, \"count\": 1000, " + means + ", " + quats + ", \"scales\": {\"codebook\": " +
                   codebook(-9, 1) + ", \"files\": [\"scales.webp\"]}, \"sh0\": {\"codebook\": " + codebook(-2, 2) +
                   ", \"files\": [\"sh0.webp\"]}, \"shN\": {\"count\": 4096, \"bands\": 2, \"codebook\": " +
                   codebook(-1, 1) + ", \"files\": [\"shN_centroids.webp\", \"shN_labels.webp\"]}}\n");
    write.text(
        "sog_meta", "v1_sh1.json",
        "{\"means\": {\"shape\": [1000, 3], \"dtype\": \"float32\", \"mins\": [-2, -1.5, -3], \"maxs\": [2.5, 1, 3], "
        "\"files\": [\"means_l.webp\", \"means_u.webp\"]}, " +
            quats +
            ", \"scales\": {\"shape\": [1000, 3], \"mins\": [-9, -9, -8], \"maxs\": [0, 1, 0.5], \"files\": "
            "[\"scales.webp\"]}, \"sh0\": {\"shape\": [1000, 1, 4], \"mins\": [-2, -2, -2, -6], \"maxs\": [2, 2, "
            "2, 6], \"files\": [\"sh0.webp\"]}, \"shN\": {\"shape\": [1000, 9], \"mins\": -1.5, \"maxs\": 1.5, "
            "\"files\": [\"shN_centroids.webp\", \"shN_labels.webp\"]}}\n");
    // Lossless WebP textures as SOG writes them, behind the harness's min_pixels byte.
    for (const auto& [w, h, min_pixels] :
         {std::array<int, 3>{4, 4, 16}, std::array<int, 3>{64, 1, 0}, std::array<int, 3>{3, 5, 255}}) {
        std::vector<std::uint8_t> rgba;
        for (int i = 0; i < w * h; ++i)
            for (int c = 0; c < 4; ++c) rgba.push_back(static_cast<std::uint8_t>(37 * i + 80 * c));
        std::uint8_t* encoded = nullptr;
        const std::size_t size = WebPEncodeLosslessRGBA(rgba.data(), w, h, 4 * w, &encoded);
        Bytes seed{static_cast<std::uint8_t>(min_pixels)};
        seed.insert(seed.end(), encoded, encoded + size);
        WebPFree(encoded);
        write("sog_webp", std::to_string(w) + "x" + std::to_string(h) + ".webp", seed);
    }
}

// The sample world's prop meshes (.glb) and one of them as .gltf with embedded buffers.
void gltf_seeds(SeedWriter& write) {
    const fs::path dir = splat_fuzz::sandbox_dir() / "seed_meshes";
    splat_lod::world::write_prop_meshes(dir);
    for (const char* name : {"post", "fence", "house"})
        write("gltf", std::string(name) + ".glb",
              engine::read_binary_file(dir / "meshes" / (std::string(name) + ".glb")));
    tinygltf::TinyGLTF gltf;
    tinygltf::Model model;
    std::string err, warn;
    if (!gltf.LoadBinaryFromFile(&model, &err, &warn, (dir / "meshes/post.glb").string()))
        engine::fail("post.glb: " + err);
    std::ostringstream text;
    gltf.WriteGltfSceneToStream(&model, text, false, false);
    write.text("gltf", "post_embedded.gltf", text.str());
}

// ---- Seeds cut down from the real files in tests/data and --shared-data (../shared/data).

// A real file by its path relative to the data folders: tests/data/<relative> when it is kept
// there, else <shared>/<relative> (none without --shared-data).
struct RealFiles {
    fs::path shared;

    fs::path operator()(const std::string& relative) const {
        std::error_code ec;
        const fs::path kept = engine::test::source_dir() / "data" / relative;
        if (fs::exists(kept, ec) || shared.empty()) return kept;
        return shared / relative;
    }
};

Bytes read_or_empty(const fs::path& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec) ? engine::read_binary_file(path) : Bytes{};
}

void real_splat_seeds(SeedWriter& write, const RealFiles& real) {
    using splat_io_test::encode_spz;
    const auto donut = read_or_empty(real("splats/gshairlod-donut/fused.ply"));
    if (!donut.empty()) {
        write("inria_ply", "real_donut_16.ply",
              write_tables(tables_of(donut), "binary_little_endian", {{"vertex", 16}}));
        auto cloud = splat_lod::read_ply(donut, "fused.ply");
        std::vector<std::uint32_t> first(32);
        for (std::uint32_t i = 0; i < first.size(); ++i) first[i] = i;
        write("antimatter_splat", "real_donut_32.splat", splat_lod::encode_antimatter_splat(cloud.permuted(first)));
    }
    for (const char* scene : {"biker", "guitar"}) {
        const auto bytes = read_or_empty(real("splats/playcanvas-engine/" + std::string(scene) + ".compressed.ply"));
        if (bytes.empty()) continue;
        const auto cut =
            write_tables(tables_of(bytes), "binary_little_endian", {{"chunk", 1}, {"vertex", 256}, {"sh", 256}});
        write("compressed_ply", std::string("real_") + scene + "_256.compressed.ply", cut);
    }
    const auto fixture = read_or_empty(real("splats/playcanvas-engine/test-fixture-64.compressed.ply"));
    if (!fixture.empty()) write("compressed_ply", "real_test-fixture-64.compressed.ply", fixture);
    const auto biker = read_or_empty(real("splats/playcanvas-engine/biker.spz"));
    if (!biker.empty()) {
        auto cloud = splat_lod::read_spz(biker, "biker.spz");
        std::vector<std::uint32_t> first(48);
        for (std::uint32_t i = 0; i < first.size(); ++i) first[i] = i;
        cloud = cloud.permuted(first);
        write("spz", "real_biker_48_v4.spz", encode_spz(cloud, 4));
        write("spz", "real_biker_48_v3.spz", encode_spz(cloud, 3));
        write("spz", "real_biker_head.spz", std::span(biker.data(), std::min<std::size_t>(biker.size(), 4096)));
        write("antimatter_splat", "real_biker_48.splat", splat_lod::encode_antimatter_splat(cloud));
    }
}

void real_other_seeds(SeedWriter& write, const RealFiles& real) {
    const std::string pc = "splats/playcanvas-engine/";
    const std::pair<std::string, std::string> copies[] = {
        {pc + "playcanvas-logo-sog/meta.json", "sog_meta/real_logo_v1.json"},
        {pc + "playbot-lod-sog/6_0/meta.json", "sog_meta/real_playbot_6_v2.json"},
        {pc + "playbot-lod-sog/lod-meta.json", "sog_meta/real_playbot_lod-meta.json"},
        {"gltf/online3dviewer/Box/glTF-Embedded/Box.gltf", "gltf/real_box_embedded.gltf"},
        {"gltf/online3dviewer/Box/glTF-Binary/Box.glb", "gltf/real_box.glb"},
        {"gltf/online3dviewer/Box/glTF-Draco/Box.gltf", "gltf/real_box_draco.gltf"},
        {"gltf/online3dviewer/BoxTextured/glTF-Binary/BoxTextured.glb", "gltf/real_box_textured.glb"},
        {"gltf/online3dviewer/BoxTextured/glTF-Embedded/BoxTextured.gltf", "gltf/real_box_textured_embedded.gltf"},
        {"gltf/tinygltf/Cube/Cube.gltf", "gltf/real_cube_external.gltf"}};
    for (const auto& [from, to] : copies) {
        const auto bytes = read_or_empty(real(from));
        if (!bytes.empty()) write(fs::path(to).parent_path().string(), fs::path(to).filename().string(), bytes);
    }
    for (const char* texture : {"shN_labels", "means_u", "quats"}) {
        auto bytes = read_or_empty(real(pc + "playbot-lod-sog/6_0/" + texture + ".webp"));
        if (bytes.empty()) continue;
        bytes.insert(bytes.begin(), 0);  // min_pixels
        write("sog_webp", std::string("real_playbot_6_") + texture + ".webp", bytes);
    }
}

}  // namespace

int main(int argc, char** argv) {
    fs::path out, shared;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string flag = argv[i];
        if (flag == "--out")
            out = argv[i + 1];
        else if (flag == "--shared-data")
            shared = argv[i + 1];
    }
    if (out.empty()) {
        std::fprintf(stderr, "usage: fuzz_seed_maker --out DIR [--shared-data DIR]\n");
        return 2;
    }
    try {
        SeedWriter write{out};
        ply_seeds(write);
        splat_and_spz_seeds(write);
        sog_seeds(write);
        gltf_seeds(write);
        world_chunk_seeds(write);
        compact_chunk_seeds(write, out);
        const int made = write.written;
        const RealFiles real{shared};
        real_splat_seeds(write, real);
        real_other_seeds(write, real);
        std::printf("fuzz_seed_maker: %d project-made seeds, %d cut from real files, in %s\n", made,
                    write.written - made, out.c_str());
    } catch (const engine::Error& e) {
        std::fprintf(stderr, "fuzz_seed_maker: %s\n", e.what());
        return 1;
    }
    return 0;
}
