#pragma once
// Internal to world_manifest.cpp: the optional keys of imported worlds ("ground", "capture"), read with
// the same strictness as the rest of the manifest (errors "<file>: ground.heights: <problem>").
#include <string>

#include <nlohmann/json.hpp>

#include "splat_lod/core/world_manifest.h"

namespace splat_lod::world {

GroundGrid parse_ground_grid(const nlohmann::json& value, const std::string& file);
nlohmann::json ground_grid_json(const GroundGrid& ground);
CaptureOrigin parse_capture_origin(const nlohmann::json& value, const std::string& file);
nlohmann::json capture_origin_json(const CaptureOrigin& capture);

}  // namespace splat_lod::world
