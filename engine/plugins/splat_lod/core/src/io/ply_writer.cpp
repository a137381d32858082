// INRIA PLY writer: binary little-endian, the full layout for the cloud's SH degree, then the
// extra properties, then the LOD attributes when any Gaussian uses them.
#include <algorithm>
#include <set>
#include <string>

#include "engine/core/file_io.h"
#include "io_util.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod {
namespace {

class RowWriter {
public:
    explicit RowWriter(std::uint8_t* out) : out_(out) {}
    void f32(float v) {
        io::store_f32le(out_, v);
        out_ += 4;
    }
    void vec3(const glm::vec3& v) {
        f32(v.x);
        f32(v.y);
        f32(v.z);
    }
    void u8(std::uint8_t v) { *out_++ = v; }

private:
    std::uint8_t* out_;
};

std::string make_header(const SplatCloud& cloud, bool lod) {
    std::string h = "ply\nformat binary_little_endian 1.0\ncomment written by splat_lod\n";
    if (lod && cloud.level_handover != LevelHandover::unknown)
        h += "comment " + std::string(kLevelHandoverComment) + " " + level_handover_name(cloud.level_handover) + "\n";
    h += "element vertex " + std::to_string(cloud.size()) + "\n";
    auto prop = [&h](const std::string& name) { h += "property float " + name + "\n"; };
    for (const char* name : {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"}) prop(name);
    for (std::size_t i = 0; i < cloud.sh_rest_stride(); ++i) prop("f_rest_" + std::to_string(i));
    for (const char* name : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
        prop(name);
    for (const auto& extra : cloud.extras) prop(extra.name);
    if (lod) {
        prop("coverage_min");
        prop("coverage_max");
        h += "property uchar lod_level\n";
    }
    h += "end_header\n";
    return h;
}

// Extra names must be single header words that do not collide with the layout's own names,
// or the file could not be read back.
void check_extra_names(const SplatCloud& cloud) {
    static const std::set<std::string> reserved = {"x",       "y",       "z",         "nx",           "ny",
                                                   "nz",      "f_dc_0",  "f_dc_1",    "f_dc_2",       "opacity",
                                                   "scale_0", "scale_1", "scale_2",   "rot_0",        "rot_1",
                                                   "rot_2",   "rot_3",   "lod_level", "coverage_min", "coverage_max"};
    std::set<std::string> seen;
    for (const auto& extra : cloud.extras) {
        const bool bad_char =
            std::any_of(extra.name.begin(), extra.name.end(), [](char c) { return c <= ' ' || c > '~'; });
        const bool taken =
            reserved.count(extra.name) || extra.name.rfind("f_rest_", 0) == 0 || !seen.insert(extra.name).second;
        if (extra.name.empty() || bad_char || taken)
            engine::fail("splat_lod::write_inria_ply(): extra property name \"" + extra.name +
                         "\" cannot be written to a PLY header (empty, not a single word, or already used)");
    }
}

void write_row(const SplatCloud& cloud, std::size_t i, bool lod, std::uint8_t* out) {
    RowWriter row(out);
    row.vec3(cloud.positions[i]);
    row.vec3(glm::vec3(0.0f));  // normals: unused, kept for viewers that expect them
    row.vec3(cloud.sh_dc[i]);
    // INRIA's f_rest is channel-major: all of R's coefficients, then G's, then B's.
    const int coeffs = sh_rest_coeffs(cloud.sh_degree);
    for (int c = 0; c < 3; ++c)
        for (int k = 1; k <= coeffs; ++k) row.f32(cloud.sh_rest_at(i, k, c));
    row.f32(cloud.opacity_logits[i]);
    row.vec3(cloud.log_scales[i]);
    const Rotation& r = cloud.rotations[i];
    row.f32(r.w);
    row.f32(r.x);
    row.f32(r.y);
    row.f32(r.z);
    for (const auto& extra : cloud.extras) row.f32(extra.values[i]);
    if (lod) {
        row.f32(cloud.coverage_min[i]);
        row.f32(cloud.coverage_max[i]);
        row.u8(cloud.lod_level[i]);
    }
}

}  // namespace

std::vector<std::uint8_t> encode_inria_ply(const SplatCloud& cloud) {
    cloud.check_consistent();
    check_extra_names(cloud);
    const bool lod = cloud.has_lod_attributes();
    const std::string header = make_header(cloud, lod);
    const std::size_t floats = 17 + cloud.sh_rest_stride() + cloud.extras.size() + (lod ? 2 : 0);
    const std::size_t row_size = floats * 4 + (lod ? 1 : 0);
    std::vector<std::uint8_t> bytes(header.size() + row_size * cloud.size());
    std::copy(header.begin(), header.end(), bytes.begin());
    for (std::size_t i = 0; i < cloud.size(); ++i)
        write_row(cloud, i, lod, bytes.data() + header.size() + i * row_size);
    return bytes;
}

void write_inria_ply(const std::filesystem::path& path, const SplatCloud& cloud) {
    engine::write_file_atomic(path, encode_inria_ply(cloud));
}

}  // namespace splat_lod
