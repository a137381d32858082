#include "engine/scene/json_fields.h"

#include <cmath>
#include <cstdint>
#include <limits>

namespace engine::json_fields {
namespace {

const nlohmann::json* find(const nlohmann::json& object, const char* key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

float finite_number(const nlohmann::json& value, const std::string& key, const ComponentLoadContext& ctx) {
    if (!value.is_number()) ctx.error(key, "expected a number, got " + value.dump());
    const double v = value.get<double>();
    if (!std::isfinite(v)) ctx.error(key, "expected a finite number");
    if (std::abs(v) > std::numeric_limits<float>::max()) ctx.error(key, "beyond float range: " + value.dump());
    return static_cast<float>(v);
}

template <int N>
glm::vec<N, float> vector(const nlohmann::json& object, const char* key, const glm::vec<N, float>& fallback,
                          const ComponentLoadContext& ctx) {
    const auto* value = find(object, key);
    if (!value) return fallback;
    if (!value->is_array() || value->size() != N)
        ctx.error(key, "expected an array of " + std::to_string(N) + " numbers, got " + value->dump());
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i)
        out[i] =
            finite_number((*value)[static_cast<std::size_t>(i)], std::string(key) + "[" + std::to_string(i) + "]", ctx);
    return out;
}

}  // namespace

float number(const nlohmann::json& object, const char* key, float fallback, const ComponentLoadContext& ctx) {
    const auto* value = find(object, key);
    return value ? finite_number(*value, key, ctx) : fallback;
}

int integer(const nlohmann::json& object, const char* key, int fallback, const ComponentLoadContext& ctx) {
    const auto* value = find(object, key);
    if (!value) return fallback;
    if (!value->is_number_integer()) ctx.error(key, "expected an integer, got " + value->dump());
    // get<int>() would wrap larger values silently (4294967296 would read as 0).
    const bool fits = value->is_number_unsigned()
                          ? value->get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<int>::max())
                          : value->get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                                value->get<std::int64_t>() <= std::numeric_limits<int>::max();
    if (!fits) ctx.error(key, "out of range: " + value->dump());
    return value->get<int>();
}

bool boolean(const nlohmann::json& object, const char* key, bool fallback, const ComponentLoadContext& ctx) {
    const auto* value = find(object, key);
    if (!value) return fallback;
    if (!value->is_boolean()) ctx.error(key, "expected true or false, got " + value->dump());
    return value->get<bool>();
}

std::string string(const nlohmann::json& object, const char* key, const std::string& fallback,
                   const ComponentLoadContext& ctx) {
    const auto* value = find(object, key);
    if (!value) return fallback;
    if (!value->is_string()) ctx.error(key, "expected a string, got " + value->dump());
    return value->get<std::string>();
}

std::string required_string(const nlohmann::json& object, const char* key, const ComponentLoadContext& ctx) {
    if (!find(object, key)) ctx.error(key, "missing (required)");
    return string(object, key, "", ctx);
}

glm::vec3 vec3(const nlohmann::json& object, const char* key, const glm::vec3& fallback,
               const ComponentLoadContext& ctx) {
    return vector<3>(object, key, fallback, ctx);
}

glm::vec4 vec4(const nlohmann::json& object, const char* key, const glm::vec4& fallback,
               const ComponentLoadContext& ctx) {
    return vector<4>(object, key, fallback, ctx);
}

void only_keys(const nlohmann::json& object, std::initializer_list<const char*> allowed,
               const ComponentLoadContext& ctx) {
    for (const auto& item : object.items()) {
        bool ok = false;
        for (const char* a : allowed) ok = ok || item.key() == a;
        if (!ok) {
            std::string list;
            for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
            ctx.error(item.key(), "unknown key (allowed: " + list + ")");
        }
    }
}

}  // namespace engine::json_fields
