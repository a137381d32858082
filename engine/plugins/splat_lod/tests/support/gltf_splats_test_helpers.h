#pragma once
// Test-only glTF builder for the KHR_gaussian_splatting tests: a document (JSON with an embedded
// base64 buffer) from a cloud, with each attribute's component type chosen, so that the reader's
// quantised paths and its checks can be fed files the project's writer never makes.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "splat_lod/core/splat_cloud.h"

namespace gltf_test {

constexpr int kFloat = 5126, kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123;

struct Encoding {
    int component = kFloat;
    bool normalized = false;
};

struct Encodings {
    Encoding rotation, scale, opacity;
};

inline std::string base64(const std::vector<std::uint8_t>& bytes) {
    static constexpr char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t v = static_cast<std::uint32_t>(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= static_cast<std::uint32_t>(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= bytes[i + 2];
        out += digits[v >> 18 & 63];
        out += digits[v >> 12 & 63];
        out += i + 1 < bytes.size() ? digits[v >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? digits[v & 63] : '=';
    }
    return out;
}

// Builds the document attribute by attribute; buffer() embeds the bytes.
struct Builder {
    nlohmann::json doc = {{"asset", {{"version", "2.0"}}},
                          {"extensionsUsed", {"KHR_gaussian_splatting"}},
                          {"scene", 0},
                          {"scenes", {{{"nodes", {0}}}}},
                          {"nodes", {{{"mesh", 0}}}},
                          {"meshes", {{{"primitives", nlohmann::json::array()}}}},
                          {"accessors", nlohmann::json::array()},
                          {"bufferViews", nlohmann::json::array()}};
    std::vector<std::uint8_t> bytes;

    void put(double v, Encoding e) {
        auto raw = [&](auto x) {
            const std::size_t at = bytes.size();
            bytes.resize(at + sizeof x);
            std::memcpy(bytes.data() + at, &x, sizeof x);
        };
        const double scale = !e.normalized            ? 1.0
                             : e.component == kUByte  ? 255.0
                             : e.component == kByte   ? 127.0
                             : e.component == kUShort ? 65535.0
                                                      : 32767.0;
        const double q = std::round(v * scale);
        switch (e.component) {
            case kUByte:
                raw(static_cast<std::uint8_t>(q));
                break;
            case kByte:
                raw(static_cast<std::int8_t>(q));
                break;
            case kUShort:
                raw(static_cast<std::uint16_t>(q));
                break;
            case kShort:
                raw(static_cast<std::int16_t>(q));
                break;
            default:
                raw(static_cast<float>(v));
        }
    }
    // Returns the accessor index.
    int accessor(const std::vector<double>& values, const char* type, std::size_t count, Encoding e) {
        const std::size_t offset = bytes.size();
        for (double v : values) put(v, e);
        const std::size_t length = bytes.size() - offset;
        bytes.resize((bytes.size() + 3) / 4 * 4, 0);
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}});
        nlohmann::json a = {{"bufferView", doc["bufferViews"].size() - 1},
                            {"componentType", e.component},
                            {"count", count},
                            {"type", type}};
        if (e.normalized) a["normalized"] = true;
        doc["accessors"].push_back(a);
        return static_cast<int>(doc["accessors"].size() - 1);
    }
    // A splat primitive of `cloud` (in mesh `mesh`, created when missing).
    void primitive(const splat_lod::SplatCloud& cloud, const Encodings& enc = {}, std::size_t mesh = 0) {
        const std::size_t n = cloud.size();
        std::vector<double> pos, rot, scale, opacity, dc;
        for (std::size_t i = 0; i < n; ++i) {
            const auto& r = cloud.rotations[i];
            pos.insert(pos.end(), {cloud.positions[i].x, cloud.positions[i].y, cloud.positions[i].z});
            rot.insert(rot.end(), {r.x, r.y, r.z, r.w});
            for (int c = 0; c < 3; ++c) scale.push_back(std::exp(double(cloud.log_scales[i][c])));
            opacity.push_back(1.0 / (1.0 + std::exp(-double(cloud.opacity_logits[i]))));
            dc.insert(dc.end(), {cloud.sh_dc[i].x, cloud.sh_dc[i].y, cloud.sh_dc[i].z});
        }
        nlohmann::json attributes = {{"POSITION", accessor(pos, "VEC3", n, {})},
                                     {"KHR_gaussian_splatting:ROTATION", accessor(rot, "VEC4", n, enc.rotation)},
                                     {"KHR_gaussian_splatting:SCALE", accessor(scale, "VEC3", n, enc.scale)},
                                     {"KHR_gaussian_splatting:OPACITY", accessor(opacity, "SCALAR", n, enc.opacity)},
                                     {"KHR_gaussian_splatting:SH_DEGREE_0_COEF_0", accessor(dc, "VEC3", n, {})}};
        for (int l = 1; l <= cloud.sh_degree; ++l)
            for (int m = 0; m <= 2 * l; ++m) {
                std::vector<double> v;
                for (std::size_t i = 0; i < n; ++i)
                    for (int c = 0; c < 3; ++c) v.push_back(cloud.sh_rest_at(i, l * l + m, c));
                attributes["KHR_gaussian_splatting:SH_DEGREE_" + std::to_string(l) + "_COEF_" + std::to_string(m)] =
                    accessor(v, "VEC3", n, {});
            }
        while (doc["meshes"].size() <= mesh) doc["meshes"].push_back({{"primitives", nlohmann::json::array()}});
        doc["meshes"][mesh]["primitives"].push_back(
            {{"attributes", attributes},
             {"mode", 0},
             {"extensions",
              {{"KHR_gaussian_splatting", {{"kernel", "ellipse"}, {"colorSpace", "srgb_rec709_display"}}}}}});
    }
    nlohmann::json& prim(std::size_t mesh = 0, std::size_t p = 0) { return doc["meshes"][mesh]["primitives"][p]; }
    std::vector<std::uint8_t> file() {
        doc["buffers"] = {
            {{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}};
        const std::string text = doc.dump();
        return {text.begin(), text.end()};
    }
};

}  // namespace gltf_test
