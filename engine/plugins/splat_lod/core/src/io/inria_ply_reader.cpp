// INRIA 3DGS PLY reader (full and reduced layouts, extra properties kept) and the read_ply entry
// point that also dispatches to the compressed-PLY decoder.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <set>

#include "engine/core/file_io.h"
#include "engine/core/log.h"
#include "io_util.h"
#include "readers.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod::io {
namespace {

const std::set<std::string>& standard_names() {
    static const std::set<std::string> names = {"x",       "y",       "z",         "nx",           "ny",
                                                "nz",      "f_dc_0",  "f_dc_1",    "f_dc_2",       "opacity",
                                                "scale_0", "scale_1", "scale_2",   "rot_0",        "rot_1",
                                                "rot_2",   "rot_3",   "lod_level", "coverage_min", "coverage_max"};
    return names;
}

bool is_f_rest(const std::string& name) {
    return name.rfind("f_rest_", 0) == 0;
}

// The SH degree implied by the f_rest_* properties, which must be f_rest_0..f_rest_{M-1}.
int sh_degree_from_f_rest(const PlyFile& ply, const PlyElement& vertex) {
    std::vector<int> indices;
    for (const auto& p : vertex.properties) {
        if (!is_f_rest(p.name)) continue;
        const std::string digits = p.name.substr(7);
        int index = -1;
        const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), index);
        if (result.ec != std::errc() || result.ptr != digits.data() + digits.size() || index < 0)
            fail_file(ply.name, "vertex property \"" + p.name + "\" is not f_rest_<number>");
        indices.push_back(index);
    }
    std::sort(indices.begin(), indices.end());
    for (std::size_t i = 0; i < indices.size(); ++i)
        if (indices[i] != static_cast<int>(i))
            fail_file(ply.name, "f_rest_* properties are not numbered 0.." + std::to_string(indices.size() - 1));
    for (int degree = 0; degree <= kMaxShDegree; ++degree)
        if (indices.size() == static_cast<std::size_t>(3 * sh_rest_coeffs(degree))) return degree;
    fail_file(ply.name,
              std::to_string(indices.size()) + " f_rest_* properties: expected 0, 9, 24 or 45 (SH degree 0..3)");
}

class InriaDecoder {
public:
    InriaDecoder(const PlyFile& ply, const PlyElement& vertex) : ply_(ply), vertex_(vertex) {}

    SplatCloud decode(LoadReport& report) {
        SplatCloud cloud;
        cloud.sh_degree = sh_degree_from_f_rest(ply_, vertex_);
        cloud.resize(static_cast<std::size_t>(vertex_.count));
        read_vec3(cloud.positions, "x", "y", "z");
        read_vec3(cloud.log_scales, "scale_0", "scale_1", "scale_2");
        read_vec3(cloud.sh_dc, "f_dc_0", "f_dc_1", "f_dc_2");
        cloud.opacity_logits = required("opacity");
        read_rotations(cloud);
        read_sh_rest(cloud);
        read_lod_attributes(cloud, report);
        read_extras(cloud);
        return cloud;
    }

private:
    std::vector<float> required(const std::string& name) const {
        const PlyProperty* p = vertex_.find(name);
        if (!p) fail_file(ply_.name, "vertex element has no property \"" + name + "\"");
        return ply_.column_f32(vertex_, *p);
    }

    void read_vec3(std::vector<glm::vec3>& out, const char* a, const char* b, const char* c) const {
        const auto xs = required(a), ys = required(b), zs = required(c);
        for (std::size_t i = 0; i < out.size(); ++i) out[i] = {xs[i], ys[i], zs[i]};
    }

    void read_rotations(SplatCloud& cloud) const {
        const auto w = required("rot_0"), x = required("rot_1"), y = required("rot_2"), z = required("rot_3");
        for (std::size_t i = 0; i < cloud.size(); ++i) cloud.rotations[i] = {w[i], x[i], y[i], z[i]};
    }

    // f_rest is channel-major in the file (f_rest_{c*K + k}); the cloud is coefficient-major.
    void read_sh_rest(SplatCloud& cloud) const {
        const int coeffs = sh_rest_coeffs(cloud.sh_degree);
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < coeffs; ++k) {
                const auto values = required("f_rest_" + std::to_string(c * coeffs + k));
                for (std::size_t i = 0; i < cloud.size(); ++i) cloud.sh_rest_at(i, k + 1, c) = values[i];
            }
    }

    void read_lod_attributes(SplatCloud& cloud, LoadReport& report) const {
        read_level_handover(cloud, report);
        if (vertex_.find("coverage_min")) cloud.coverage_min = required("coverage_min");
        if (vertex_.find("coverage_max")) cloud.coverage_max = required("coverage_max");
        if (!vertex_.find("lod_level")) return;
        const auto levels = required("lod_level");
        std::size_t clamped = 0;
        for (std::size_t i = 0; i < cloud.size(); ++i) {
            const float v = levels[i];
            // A non-finite level makes the Gaussian non-finite, so sanitise drops and counts it.
            if (!std::isfinite(v)) {
                cloud.coverage_min[i] = std::numeric_limits<float>::quiet_NaN();
                continue;
            }
            const float level = std::clamp(std::round(v), 0.0f, 255.0f);
            if (level != v) ++clamped;
            cloud.lod_level[i] = static_cast<std::uint8_t>(level);
        }
        if (clamped > 0)
            report.warnings.push_back(std::to_string(clamped) +
                                      " lod_level values were not integers in 0..255 and were rounded/clamped");
    }

    // The header comment write_inria_ply leaves for a baked cloud (kLevelHandoverComment).
    void read_level_handover(SplatCloud& cloud, LoadReport& report) const {
        const std::string prefix = std::string(kLevelHandoverComment) + " ";
        for (const std::string& comment : ply_.comments) {
            if (comment.rfind(prefix, 0) != 0) continue;
            const std::string value = comment.substr(prefix.size());
            if (const auto handover = parse_level_handover(value)) {
                cloud.level_handover = *handover;
            } else {
                report.warnings.push_back("unknown level handover \"" + value + "\" in the header, read as unknown");
            }
        }
    }

    void read_extras(SplatCloud& cloud) const {
        for (const auto& p : vertex_.properties) {
            if (standard_names().count(p.name) || is_f_rest(p.name)) continue;
            cloud.extras.push_back({p.name, ply_.column_f32(vertex_, p)});
        }
    }

    const PlyFile& ply_;
    const PlyElement& vertex_;
};

const char* format_name(PlyFormat format) {
    switch (format) {
        case PlyFormat::ascii:
            return "ascii";
        case PlyFormat::binary_little_endian:
            return "binary_little_endian";
        case PlyFormat::binary_big_endian:
            return "binary_big_endian";
    }
    return "?";
}

}  // namespace

SplatCloud decode_inria_ply(const PlyFile& ply, LoadReport& report) {
    const PlyElement* vertex = ply.find_element("vertex");
    if (!vertex) fail_file(ply.name, "PLY has no \"vertex\" element");
    for (const auto& e : ply.elements)
        if (e.name != "vertex") report.warnings.push_back("element \"" + e.name + "\" ignored");
    report.format = std::string("INRIA PLY (") + format_name(ply.format) + ")";
    report.gaussians_in_file = static_cast<std::size_t>(vertex->count);
    return InriaDecoder(ply, *vertex).decode(report);
}

void finish_load(SplatCloud& cloud, LoadReport& report, LoadReport* caller, const std::string& name) {
    sanitise(cloud, &report);
    if (caller) {
        *caller = std::move(report);
        return;
    }
    for (const auto& warning : report.warnings) engine::log_warning(name + ": " + warning);
    if (report.dropped() > 0)
        engine::log_warning(name + ": dropped " + std::to_string(report.dropped_non_finite) +
                            " Gaussians with NaN/Inf values and " + std::to_string(report.dropped_zero_rotation) +
                            " with a zero quaternion");
}

}  // namespace splat_lod::io

namespace splat_lod {

SplatCloud read_ply(std::span<const std::uint8_t> bytes, const std::string& name, LoadReport* report) {
    const io::PlyFile ply = io::parse_ply(bytes, name);
    LoadReport local;
    local.warnings = ply.warnings;
    SplatCloud cloud =
        io::is_compressed_ply(ply) ? io::decode_compressed_ply(ply, local) : io::decode_inria_ply(ply, local);
    io::finish_load(cloud, local, report, name);
    return cloud;
}

SplatCloud read_ply(const std::filesystem::path& path, LoadReport* report) {
    const auto bytes = engine::read_binary_file(path);
    return read_ply(bytes, path.string(), report);
}

}  // namespace splat_lod
