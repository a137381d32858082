// The manifest's optional keys of imported worlds (world_manifest_extras.h, world_manifest.h).
#include "world_manifest_extras.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace splat_lod::world {
namespace {

using nlohmann::json;

constexpr int kMaxGroundCells = 4096;

[[noreturn]] void fail(const std::string& file, const std::string& key, const std::string& problem) {
    engine::fail(file + ": " + key + ": " + problem);
}

void only_keys(const json& object, const std::string& file, const std::string& key,
               std::initializer_list<const char*> allowed) {
    if (!object.is_object()) fail(file, key, "expected an object");
    for (const auto& item : object.items())
        if (std::none_of(allowed.begin(), allowed.end(), [&](const char* name) { return item.key() == name; }))
            fail(file, key + "." + item.key(), "unknown key");
}

std::vector<double> numbers(const json& object, const std::string& file, const std::string& key, const char* name,
                            std::size_t count) {
    const auto it = object.find(name);
    if (it == object.end()) fail(file, key + "." + name, "missing (required)");
    if (!it->is_array() || (count > 0 && it->size() != count))
        fail(file, key + "." + name, "expected an array of " + std::to_string(count) + " numbers");
    std::vector<double> out;
    for (const json& v : *it) {
        if (!v.is_number() || !std::isfinite(v.get<double>())) fail(file, key + "." + name, "expected finite numbers");
        out.push_back(v.get<double>());
    }
    return out;
}

}  // namespace

float GroundGrid::height(float x, float z, float size_m) const {
    if (empty()) return 0.0f;
    const float cell = size_m / static_cast<float>(cells);
    const int i = std::clamp(static_cast<int>(std::floor((x + 0.5f * size_m) / cell)), 0, cells - 1);
    const int j = std::clamp(static_cast<int>(std::floor((z + 0.5f * size_m) / cell)), 0, cells - 1);
    return heights[static_cast<std::size_t>(j * cells + i)];
}

GroundGrid parse_ground_grid(const json& value, const std::string& file) {
    only_keys(value, file, "ground", {"cells", "heights"});
    const auto it = value.find("cells");
    if (it == value.end() || !it->is_number_integer() || it->get<long long>() < 1 ||
        it->get<long long>() > kMaxGroundCells)
        fail(file, "ground.cells", "expected an integer from 1 to " + std::to_string(kMaxGroundCells));
    GroundGrid ground;
    ground.cells = it->get<int>();
    const auto cells = static_cast<std::size_t>(ground.cells);
    for (const double h : numbers(value, file, "ground", "heights", cells * cells))
        ground.heights.push_back(static_cast<float>(h));
    return ground;
}

json ground_grid_json(const GroundGrid& ground) {
    return {{"cells", ground.cells}, {"heights", ground.heights}};
}

CaptureOrigin parse_capture_origin(const json& value, const std::string& file) {
    only_keys(value, file, "capture", {"source", "rotation", "translation"});
    CaptureOrigin capture;
    const auto source = value.find("source");
    if (source == value.end() || !source->is_string() || source->get<std::string>().empty())
        fail(file, "capture.source", "expected a non-empty string");
    capture.source = source->get<std::string>();
    const auto rotation = numbers(value, file, "capture", "rotation", 9);
    std::copy(rotation.begin(), rotation.end(), capture.rotation.begin());
    const auto translation = numbers(value, file, "capture", "translation", 3);
    std::copy(translation.begin(), translation.end(), capture.translation.begin());
    return capture;
}

json capture_origin_json(const CaptureOrigin& capture) {
    return {{"source", capture.source}, {"rotation", capture.rotation}, {"translation", capture.translation}};
}

}  // namespace splat_lod::world
