// antimatter15 ".splat": a headerless array of 32-byte records
//   0  3×f32 position
//   12 3×f32 scale (linear, not log)
//   24 4×u8  colour R,G,B = 0.5 + C0·f_dc, A = sigmoid(opacity), all ×255
//   28 4×u8  quaternion (w, x, y, z) as q·128 + 128
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "engine/core/file_io.h"
#include "io_util.h"
#include "readers.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod {
namespace {

constexpr std::size_t kRecordSize = 32;

std::uint8_t to_byte(float v) {
    return static_cast<std::uint8_t>(std::clamp(std::round(v), 0.0f, 255.0f));
}

void decode_record(const std::uint8_t* p, SplatCloud& cloud, std::size_t i) {
    cloud.positions[i] = {io::load_f32le(p), io::load_f32le(p + 4), io::load_f32le(p + 8)};
    // log(0) = -inf and log of a negative scale = NaN: sanitise drops those Gaussians and counts them.
    cloud.log_scales[i] = {std::log(io::load_f32le(p + 12)), std::log(io::load_f32le(p + 16)),
                           std::log(io::load_f32le(p + 20))};
    const glm::vec3 rgb{static_cast<float>(p[24]), static_cast<float>(p[25]), static_cast<float>(p[26])};
    cloud.sh_dc[i] = (rgb / 255.0f - glm::vec3(0.5f)) / kShC0;
    cloud.opacity_logits[i] = io::unit_to_logit(static_cast<float>(p[27]) / 255.0f);
    auto q = [p](int k) { return (static_cast<float>(p[28 + k]) - 128.0f) / 128.0f; };
    cloud.rotations[i] = {q(0), q(1), q(2), q(3)};
}

void encode_record(const SplatCloud& cloud, std::size_t i, std::uint8_t* p) {
    const glm::vec3& pos = cloud.positions[i];
    const glm::vec3 scale = glm::exp(cloud.log_scales[i]);
    for (int k = 0; k < 3; ++k) {
        io::store_f32le(p + 4 * k, pos[k]);
        io::store_f32le(p + 12 + 4 * k, scale[k]);
    }
    const glm::vec3 rgb = (glm::vec3(0.5f) + kShC0 * cloud.sh_dc[i]) * 255.0f;
    p[24] = to_byte(rgb.x);
    p[25] = to_byte(rgb.y);
    p[26] = to_byte(rgb.z);
    p[27] = to_byte(io::sigmoid(cloud.opacity_logits[i]) * 255.0f);
    const Rotation& r = cloud.rotations[i];
    const float len = std::sqrt(r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z);
    const float inv = len > 0.0f ? 1.0f / len : 0.0f;
    const float q[4] = {r.w * inv, r.x * inv, r.y * inv, r.z * inv};
    for (int k = 0; k < 4; ++k) p[28 + k] = to_byte(q[k] * 128.0f + 128.0f);
}

}  // namespace

SplatCloud read_antimatter_splat(std::span<const std::uint8_t> bytes, const std::string& name, LoadReport* report) {
    if (bytes.size() % kRecordSize != 0)
        io::fail_file(name, "size " + std::to_string(bytes.size()) + " is not a multiple of the 32-byte .splat record");
    LoadReport local;
    local.format = "antimatter15 .splat";
    const std::size_t n = bytes.size() / kRecordSize;
    local.gaussians_in_file = n;
    SplatCloud cloud;
    cloud.resize(n);
    for (std::size_t i = 0; i < n; ++i) decode_record(bytes.data() + i * kRecordSize, cloud, i);
    io::finish_load(cloud, local, report, name);
    return cloud;
}

SplatCloud read_antimatter_splat(const std::filesystem::path& path, LoadReport* report) {
    const auto bytes = engine::read_binary_file(path);
    return read_antimatter_splat(bytes, path.string(), report);
}

std::vector<std::uint8_t> encode_antimatter_splat(const SplatCloud& cloud) {
    cloud.check_consistent();
    std::vector<std::uint8_t> bytes(cloud.size() * kRecordSize);
    for (std::size_t i = 0; i < cloud.size(); ++i) encode_record(cloud, i, bytes.data() + i * kRecordSize);
    return bytes;
}

void write_antimatter_splat(const std::filesystem::path& path, const SplatCloud& cloud) {
    engine::write_file_atomic(path, encode_antimatter_splat(cloud));
}

}  // namespace splat_lod
