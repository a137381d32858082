// glTF writer for KHR_gaussian_splatting: one node, one mesh, one POINTS primitive with float
// attributes, the LOD attributes and extras as _SPLAT_LOD_* attributes; .glb or .gltf with the buffer
// embedded as base64. The values written read back to the same cloud, so a file read and written
// again gives the same bytes (scales, opacities and quaternions are chosen for that, see below).
#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "engine/core/file_io.h"
#include "gltf_splats.h"
#include "io_util.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod {
namespace {

using Json = nlohmann::ordered_json;

// The smallest positive float s near forward(target) whose read-back value back(s) is closest to
// `target`: back is non-decreasing, so a binary search over the float bit patterns (ordered like the
// floats) finds it. Choosing the smallest of the floats that read back alike makes the choice stable:
// the value read back maps to the same s. Targets out of reach are replaced by what their guess reads
// back as, once.
template <typename Forward, typename Back>
float stable_preimage(float target, Forward forward, Back back, bool retry = true) {
    const float guess = forward(target);
    if (!std::isfinite(guess) || guess <= 0.0f) return guess;
    const auto bits = std::bit_cast<std::uint32_t>(guess);
    std::uint32_t lo = bits > 4096 ? bits - 4096 : 1, hi = std::min<std::uint32_t>(bits + 4096, 0x7f7fffffu);
    if (!(back(std::bit_cast<float>(lo)) < target) || back(std::bit_cast<float>(hi)) < target)
        return retry ? stable_preimage(back(guess), forward, back, false) : guess;
    while (hi - lo > 1) {  // back(lo) < target <= back(hi)
        const std::uint32_t mid = lo + (hi - lo) / 2;
        (back(std::bit_cast<float>(mid)) < target ? lo : hi) = mid;
    }
    const float below = std::bit_cast<float>(lo), above = std::bit_cast<float>(hi);
    if (back(above) - target <= target - back(below)) return above;
    return retry ? stable_preimage(back(below), forward, back, false) : below;
}

float scale_to_write(float log_scale) {
    return stable_preimage(
        log_scale, [](float x) { return static_cast<float>(std::exp(static_cast<double>(x))); },
        [](float s) { return static_cast<float>(std::log(static_cast<double>(std::max(s, io::kGltfMinScale)))); });
}

float opacity_to_write(float logit) {
    return stable_preimage(
        logit, [](float x) { return io::sigmoid(x); }, [](float o) { return opacity_to_logit(o); });
}

Rotation normalised(const Rotation& r) {
    const double inv = 1.0 / std::sqrt(double(r.w) * r.w + double(r.x) * r.x + double(r.y) * r.y + double(r.z) * r.z);
    return {static_cast<float>(r.w * inv), static_cast<float>(r.x * inv), static_cast<float>(r.y * inv),
            static_cast<float>(r.z * inv)};
}
bool same(const Rotation& a, const Rotation& b) {
    return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z;
}

// A quaternion that normalising (as every reader does) leaves unchanged: a few normalisations, then
// single-ulp nudges of one component when they cycle.
Rotation rotation_to_write(Rotation r) {
    for (int k = 0; k < 4; ++k) {
        const Rotation n = normalised(r);
        if (same(n, r)) return r;
        r = n;
    }
    for (int step = 1; step <= 3; ++step)
        for (float Rotation::*c : {&Rotation::w, &Rotation::x, &Rotation::y, &Rotation::z})
            for (const float dir : {-2.0f, 2.0f}) {
                Rotation t = r;
                for (int u = 0; u < step; ++u) t.*c = std::nextafter(t.*c, dir);
                if (same(normalised(t), t)) return t;
            }
    return r;
}

struct Builder {
    Json accessors = Json::array();
    Json views = Json::array();
    Json attributes = Json::object();
    std::vector<std::uint8_t> buffer;

    // One tightly packed buffer view per attribute, 4-byte aligned.
    void add(const std::string& name, const std::vector<float>& values, const char* type, std::size_t count) {
        const std::size_t offset = buffer.size();
        buffer.resize(offset + values.size() * 4);
        for (std::size_t i = 0; i < values.size(); ++i) io::store_f32le(buffer.data() + offset + 4 * i, values[i]);
        add_view(name, offset, values.size() * 4, 5126, type, count);
    }
    // glTF aligns every element of a vertex attribute to 4 bytes: one byte in four, byteStride 4.
    void add_bytes(const std::string& name, const std::vector<std::uint8_t>& values) {
        const std::size_t offset = buffer.size();
        buffer.resize(offset + values.size() * 4, 0);
        for (std::size_t i = 0; i < values.size(); ++i) buffer[offset + 4 * i] = values[i];
        add_view(name, offset, values.size() * 4, 5121, "SCALAR", values.size());
        views.back()["byteStride"] = 4;
    }
    void add_view(const std::string& name, std::size_t offset, std::size_t length, int component, const char* type,
                  std::size_t count) {
        buffer.resize((buffer.size() + 3) / 4 * 4, 0);
        views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", 34962}});
        accessors.push_back(
            {{"bufferView", views.size() - 1}, {"componentType", component}, {"count", count}, {"type", type}});
        attributes[name] = accessors.size() - 1;
    }
};

void add_gaussian_attributes(Builder& b, const SplatCloud& cloud) {
    const std::size_t n = cloud.size();
    std::vector<float> pos, rot, scale, opacity, dc;
    for (std::size_t i = 0; i < n; ++i) {
        pos.insert(pos.end(), {cloud.positions[i].x, cloud.positions[i].y, cloud.positions[i].z});
        const Rotation r = rotation_to_write(cloud.rotations[i]);
        rot.insert(rot.end(), {r.x, r.y, r.z, r.w});
        for (int c = 0; c < 3; ++c) scale.push_back(scale_to_write(cloud.log_scales[i][c]));
        opacity.push_back(opacity_to_write(cloud.opacity_logits[i]));
        dc.insert(dc.end(), {cloud.sh_dc[i].x, cloud.sh_dc[i].y, cloud.sh_dc[i].z});
    }
    b.add("POSITION", pos, "VEC3", n);
    glm::vec3 lo = cloud.positions[0], hi = cloud.positions[0];
    for (const auto& p : cloud.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    b.accessors.back()["min"] = {lo.x, lo.y, lo.z};
    b.accessors.back()["max"] = {hi.x, hi.y, hi.z};
    b.add(io::kAttrRotation, rot, "VEC4", n);
    b.add(io::kAttrScale, scale, "VEC3", n);
    b.add(io::kAttrOpacity, opacity, "SCALAR", n);
    b.add(io::sh_attribute(0, 0), dc, "VEC3", n);
    for (int l = 1; l <= cloud.sh_degree; ++l)
        for (int m = 0; m <= 2 * l; ++m) {
            std::vector<float> v(3 * n);
            for (std::size_t i = 0; i < n; ++i)
                for (int c = 0; c < 3; ++c) v[3 * i + static_cast<std::size_t>(c)] = cloud.sh_rest_at(i, l * l + m, c);
            b.add(io::sh_attribute(l, m), v, "VEC3", n);
        }
}

void add_lod_attributes(Builder& b, const SplatCloud& cloud) {
    for (const auto& extra : cloud.extras) {
        if (extra.name.empty()) engine::fail("splat_lod::write_gltf_splats(): an extra property has an empty name");
        b.add(io::kAttrExtraPrefix + extra.name, extra.values, "SCALAR", cloud.size());
    }
    if (!cloud.has_lod_attributes()) return;
    b.add(io::kAttrCoverageMin, cloud.coverage_min, "SCALAR", cloud.size());
    b.add(io::kAttrCoverageMax, cloud.coverage_max, "SCALAR", cloud.size());
    b.add_bytes(io::kAttrLodLevel, cloud.lod_level);
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
    static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t v = static_cast<std::uint32_t>(bytes[i]) << 16 |
                                (i + 1 < bytes.size() ? static_cast<std::uint32_t>(bytes[i + 1]) << 8 : 0u) |
                                (i + 2 < bytes.size() ? static_cast<std::uint32_t>(bytes[i + 2]) : 0u);
        out += kDigits[v >> 18 & 63];
        out += kDigits[v >> 12 & 63];
        out += i + 1 < bytes.size() ? kDigits[v >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
    }
    return out;
}

std::vector<std::uint8_t> glb(const std::string& json, const std::vector<std::uint8_t>& bin) {
    std::string text = json;
    text.resize((text.size() + 3) / 4 * 4, ' ');
    const std::size_t total = 12 + 8 + text.size() + 8 + bin.size();
    std::vector<std::uint8_t> out(total);
    auto put = [&out](std::size_t at, std::uint32_t v) { io::store_u32le(out.data() + at, v); };
    put(0, 0x46546C67u);  // "glTF"
    put(4, 2);
    put(8, static_cast<std::uint32_t>(total));
    put(12, static_cast<std::uint32_t>(text.size()));
    put(16, 0x4E4F534Au);  // "JSON"
    std::memcpy(out.data() + 20, text.data(), text.size());
    const std::size_t bin_at = 20 + text.size();
    put(bin_at, static_cast<std::uint32_t>(bin.size()));
    put(bin_at + 4, 0x004E4942u);  // "BIN\0"
    std::copy(bin.begin(), bin.end(), out.begin() + static_cast<std::ptrdiff_t>(bin_at + 8));
    return out;
}

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

}  // namespace

std::vector<std::uint8_t> encode_gltf_splats(const SplatCloud& cloud, bool binary) {
    cloud.check_consistent();
    if (cloud.empty())
        engine::fail("splat_lod::write_gltf_splats(): the cloud is empty (glTF accessors need one element)");
    Builder b;
    add_gaussian_attributes(b, cloud);
    add_lod_attributes(b, cloud);
    const Json extension = {{"kernel", "ellipse"}, {"colorSpace", "srgb_rec709_display"}};
    Json primitive = {
        {"attributes", b.attributes}, {"mode", 0}, {"extensions", {{io::kGltfSplatExtension, extension}}}};
    if (cloud.has_lod_attributes() && cloud.level_handover != LevelHandover::unknown)
        primitive["extras"] = {{io::kExtrasLevelHandover, level_handover_name(cloud.level_handover)}};
    Json buffer = {{"byteLength", b.buffer.size()}};
    if (!binary) buffer["uri"] = "data:application/octet-stream;base64," + base64(b.buffer);
    const Json doc = {{"asset", {{"version", "2.0"}, {"generator", "splat_lod"}}},
                      {"extensionsUsed", {io::kGltfSplatExtension}},
                      {"scene", 0},
                      {"scenes", {{{"nodes", {0}}}}},
                      {"nodes", {{{"mesh", 0}}}},
                      {"meshes", {{{"primitives", {primitive}}}}},
                      {"accessors", b.accessors},
                      {"bufferViews", b.views},
                      {"buffers", {buffer}}};
    if (!binary) {
        const std::string text = doc.dump(1) + "\n";
        return {text.begin(), text.end()};
    }
    return glb(doc.dump(), b.buffer);
}

void write_gltf_splats(const std::filesystem::path& path, const SplatCloud& cloud) {
    const std::string ext = lower_extension(path);
    if (ext != ".glb" && ext != ".gltf")
        engine::fail("splat_lod::write_gltf_splats(): " + path.string() + ": expected a .glb or .gltf name");
    engine::write_file_atomic(path, encode_gltf_splats(cloud, ext == ".glb"));
}

void write_splat_file(const std::filesystem::path& path, const SplatCloud& cloud) {
    const std::string ext = lower_extension(path);
    if (ext == ".glb" || ext == ".gltf")
        write_gltf_splats(path, cloud);
    else
        write_inria_ply(path, cloud);
}

}  // namespace splat_lod
