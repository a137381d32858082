#include "splat_lod/core/sog_meta.h"

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "io_util.h"

namespace splat_lod::io {
namespace {

using nlohmann::json;

class MetaParser {
public:
    explicit MetaParser(const std::string& name) : name_(name) {}

    [[noreturn]] void fail(const std::string& key, const std::string& message) const {
        fail_file(name_, key + ": " + message);
    }

    const json& member(const json& object, const std::string& key, const std::string& path) const {
        if (!object.is_object()) fail(path, "expected an object");
        const auto it = object.find(key);
        if (it == object.end()) fail(path + "." + key, "missing");
        return *it;
    }

    float number(const json& value, const std::string& key) const {
        if (!value.is_number()) fail(key, "expected a number");
        const double v = value.get<double>();
        if (!std::isfinite(v) || std::fabs(v) > std::numeric_limits<float>::max()) fail(key, "not a finite float");
        return static_cast<float>(v);
    }

    std::uint64_t count(const json& value, const std::string& key) const {
        if (!value.is_number_unsigned()) fail(key, "expected a non-negative integer");
        return value.get<std::uint64_t>();
    }

    std::vector<float> numbers(const json& value, const std::string& key, std::size_t size) const {
        if (!value.is_array() || value.size() != size)
            fail(key, "expected an array of " + std::to_string(size) + " numbers");
        std::vector<float> out;
        for (std::size_t i = 0; i < size; ++i) out.push_back(number(value[i], key + "[" + std::to_string(i) + "]"));
        return out;
    }

    // Texture names are plain file names inside the SOG folder: no paths, so a hostile meta.json
    // cannot make us read files elsewhere.
    std::vector<std::string> files(const json& section, const std::string& key, std::size_t size) const {
        const json& list = member(section, "files", key);
        if (!list.is_array() || list.size() != size)
            fail(key + ".files", "expected an array of " + std::to_string(size) + " file names");
        std::vector<std::string> out;
        for (const auto& entry : list) {
            if (!entry.is_string()) fail(key + ".files", "expected file name strings");
            const std::string file = entry.get<std::string>();
            if (file.empty() || file == "." || file == ".." || file.find_first_of("/\\") != std::string::npos)
                fail(key + ".files", "\"" + file + "\" is not a plain file name");
            out.push_back(file);
        }
        return out;
    }

    SogQuantiser codebook(const json& section, const std::string& key) const {
        SogQuantiser q;
        q.codebook = numbers(member(section, "codebook", key), key + ".codebook", 256);
        return q;
    }

    SogQuantiser range(float lo, float hi) const {
        SogQuantiser q;
        q.lo = lo;
        q.hi = hi;
        return q;
    }

    void means(const json& root, SogMeta& meta) const {
        const json& section = member(root, "means", "meta");
        const auto lo = numbers(member(section, "mins", "means"), "means.mins", 3);
        const auto hi = numbers(member(section, "maxs", "means"), "means.maxs", 3);
        for (int k = 0; k < 3; ++k) {
            meta.means_min[static_cast<std::size_t>(k)] = lo[static_cast<std::size_t>(k)];
            meta.means_max[static_cast<std::size_t>(k)] = hi[static_cast<std::size_t>(k)];
        }
        const auto names = files(section, "means", 2);
        meta.means_lower_file = names[0];
        meta.means_upper_file = names[1];
    }

    void v2_sections(const json& root, SogMeta& meta) const {
        meta.count = count(member(root, "count", "meta"), "count");
        const json& scales = member(root, "scales", "meta");
        meta.scales.fill(codebook(scales, "scales"));
        meta.scales_file = files(scales, "scales", 1)[0];
        const json& sh0 = member(root, "sh0", "meta");
        meta.colour.fill(codebook(sh0, "sh0"));
        meta.sh0_file = files(sh0, "sh0", 1)[0];
        if (!root.contains("shN")) return;
        const json& sh_n = root["shN"];
        SogShN out;
        out.palette_count = count(member(sh_n, "count", "shN"), "shN.count");
        const std::uint64_t bands = count(member(sh_n, "bands", "shN"), "shN.bands");
        if (bands < 1 || bands > 3) fail("shN.bands", std::to_string(bands) + " is not 1..3");
        out.bands = static_cast<int>(bands);
        out.quantiser = codebook(sh_n, "shN");
        const auto names = files(sh_n, "shN", 2);
        out.centroids_file = names[0];
        out.labels_file = names[1];
        meta.sh_n = out;
    }

    void v1_sections(const json& root, SogMeta& meta) const {
        const json& shape = member(member(root, "means", "meta"), "shape", "means");
        if (!shape.is_array() || shape.empty()) fail("means.shape", "expected [count, 3]");
        meta.count = count(shape[0], "means.shape[0]");
        const json& scales = member(root, "scales", "meta");
        const auto s_lo = numbers(member(scales, "mins", "scales"), "scales.mins", 3);
        const auto s_hi = numbers(member(scales, "maxs", "scales"), "scales.maxs", 3);
        for (std::size_t k = 0; k < 3; ++k) meta.scales[k] = range(s_lo[k], s_hi[k]);
        meta.scales_file = files(scales, "scales", 1)[0];
        const json& sh0 = member(root, "sh0", "meta");
        const auto c_lo = numbers(member(sh0, "mins", "sh0"), "sh0.mins", 4);
        const auto c_hi = numbers(member(sh0, "maxs", "sh0"), "sh0.maxs", 4);
        for (std::size_t k = 0; k < 3; ++k) meta.colour[k] = range(c_lo[k], c_hi[k]);
        meta.opacity_logit = range(c_lo[3], c_hi[3]);
        meta.sh0_file = files(sh0, "sh0", 1)[0];
        if (!root.contains("shN")) return;
        const json& sh_n = root["shN"];
        SogShN out;
        out.quantiser =
            range(number(member(sh_n, "mins", "shN"), "shN.mins"), number(member(sh_n, "maxs", "shN"), "shN.maxs"));
        const auto names = files(sh_n, "shN", 2);
        out.centroids_file = names[0];
        out.labels_file = names[1];
        meta.sh_n = out;
    }

private:
    const std::string& name_;
};

}  // namespace

SogMeta parse_sog_meta(const std::string& text, const std::string& name) {
    json root;
    try {
        root = json::parse(text);
    } catch (const json::exception& e) {
        fail_file(name, std::string("malformed JSON: ") + e.what());
    }
    const MetaParser parser(name);
    if (!root.is_object()) parser.fail("meta", "expected a JSON object");
    SogMeta meta;
    if (root.contains("version")) {
        const std::uint64_t version = parser.count(root["version"], "version");
        if (version != 2) parser.fail("version", "unsupported SOG version " + std::to_string(version));
        meta.version = 2;
    }
    parser.means(root, meta);
    if (meta.version == 2)
        parser.v2_sections(root, meta);
    else
        parser.v1_sections(root, meta);
    meta.quats_file = parser.files(parser.member(root, "quats", "meta"), "quats", 1)[0];
    return meta;
}

}  // namespace splat_lod::io
