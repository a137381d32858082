// Walkthrough paths read from and written to JSON (path_file.h).
#include "sample_game/path_file.h"

#include <cmath>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"

namespace sample_game {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& where, const std::string& problem) {
    engine::fail("sample_game: " + file.string() + ": " + where + ": " + problem);
}

glm::vec3 vec3(const json& entry, const char* key, const std::filesystem::path& file, const std::string& where) {
    const auto it = entry.find(key);
    if (it == entry.end() || !it->is_array() || it->size() != 3)
        fail(file, where + "." + key, "expected an array of three numbers");
    glm::vec3 v;
    for (int k = 0; k < 3; ++k) {
        const json& x = (*it)[static_cast<std::size_t>(k)];
        if (!x.is_number() || !std::isfinite(x.get<double>())) fail(file, where + "." + key, "expected finite numbers");
        v[k] = x.get<float>();
    }
    return v;
}

Segment segment_of(const json& entry, const std::filesystem::path& file, const std::string& where) {
    const auto it = entry.find("segment");
    if (it == entry.end() || !it->is_string()) fail(file, where + ".segment", "expected a segment name");
    for (std::size_t k = 0; k < kSegmentCount; ++k)
        if (to_string(static_cast<Segment>(k)) == it->get<std::string>()) return static_cast<Segment>(k);
    fail(file, where + ".segment",
         "\"" + it->get<std::string>() + "\" is not ground, canopy, flyout, overview or return");
}

}  // namespace

std::vector<PathPose> read_path_file(const std::filesystem::path& file, int frames) {
    json doc;
    try {
        doc = json::parse(engine::read_text_file(file));
    } catch (const json::parse_error& e) {
        fail(file, "JSON", e.what());
    }
    if (!doc.is_array() || doc.size() < 2) fail(file, "top level", "expected an array of at least two poses or keys");
    const bool poses = doc[0].is_object() && doc[0].contains("forward");
    std::vector<PathPose> out;
    std::vector<PathKey> keys;
    for (std::size_t i = 0; i < doc.size(); ++i) {
        const std::string where = "[" + std::to_string(i) + "]";
        if (!doc[i].is_object()) fail(file, where, "expected an object");
        if (doc[i].contains("forward") != poses) fail(file, where, "mixes poses (\"forward\") and keys (\"look\")");
        const glm::vec3 eye = vec3(doc[i], "eye", file, where);
        const glm::vec3 direction = vec3(doc[i], poses ? "forward" : "look", file, where);
        if (!(glm::length(direction) > 1e-6f)) fail(file, where, "the view direction is zero");
        const Segment segment = segment_of(doc[i], file, where);
        if (poses)
            out.push_back(
                {eye, glm::normalize(direction), segment, static_cast<float>(i) / static_cast<float>(doc.size() - 1)});
        else
            keys.push_back({eye, direction, segment});
    }
    if (poses) return out;
    return CameraPath(keys).sample(frames, kDefaultSegmentShares);
}

void write_path_file(const std::filesystem::path& file, const std::vector<PathPose>& poses) {
    json doc = json::array();
    for (const PathPose& p : poses)
        doc.push_back({{"eye", {p.eye.x, p.eye.y, p.eye.z}},
                       {"forward", {p.forward.x, p.forward.y, p.forward.z}},
                       {"segment", std::string(to_string(p.segment))}});
    const std::string text = doc.dump(1) + "\n";
    engine::write_file_atomic(file, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace sample_game
