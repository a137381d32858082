#pragma once
// Typed reads of optional JSON fields with errors that name the scene file and the key.
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "engine/scene/component_registry.h"

namespace engine::json_fields {

float number(const nlohmann::json& object, const char* key, float fallback, const ComponentLoadContext& ctx);
int integer(const nlohmann::json& object, const char* key, int fallback, const ComponentLoadContext& ctx);
bool boolean(const nlohmann::json& object, const char* key, bool fallback, const ComponentLoadContext& ctx);
std::string string(const nlohmann::json& object, const char* key, const std::string& fallback,
                   const ComponentLoadContext& ctx);
std::string required_string(const nlohmann::json& object, const char* key, const ComponentLoadContext& ctx);
glm::vec3 vec3(const nlohmann::json& object, const char* key, const glm::vec3& fallback,
               const ComponentLoadContext& ctx);
glm::vec4 vec4(const nlohmann::json& object, const char* key, const glm::vec4& fallback,
               const ComponentLoadContext& ctx);
// Fails when the object has a key outside `allowed` (catches typos such as "fov_deg").
void only_keys(const nlohmann::json& object, std::initializer_list<const char*> allowed,
               const ComponentLoadContext& ctx);

}  // namespace engine::json_fields
