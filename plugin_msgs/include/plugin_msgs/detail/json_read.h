#pragma once
// Strict reading of message fields from JSON. Messages arrive from settings files, tools and
// tests, so a typo or a wrong type must be reported with the message kind and the key
// ("lod_settings.render_scale: ...") instead of being silently converted or ignored.
// Errors are std::invalid_argument, so this header needs nothing from the engine.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

#include <nlohmann/json.hpp>

namespace plugin_msgs::detail {

[[noreturn]] inline void field_error(std::string_view kind, std::string_view key, const std::string& message) {
    throw std::invalid_argument(std::string(kind) + "." + std::string(key) + ": " + message);
}

inline void require_object(const nlohmann::json& json, std::string_view kind) {
    if (!json.is_object())
        throw std::invalid_argument(std::string(kind) + ": expected a JSON object, got " + json.type_name());
}

// Rejects keys outside `allowed` (catches typos such as "render_scal").
inline void only_keys(const nlohmann::json& json, std::string_view kind,
                      std::initializer_list<std::string_view> allowed) {
    for (const auto& item : json.items()) {
        bool known = false;
        for (const auto key : allowed) known = known || key == item.key();
        if (known) continue;
        std::string expected;
        for (const auto key : allowed) expected += (expected.empty() ? "" : ", ") + std::string(key);
        field_error(kind, item.key(), "unknown key (expected one of: " + expected + ")");
    }
}

// nlohmann converts between number kinds silently (−1 → 2^64−1, 1.5 → 1); refuse instead.
template <class T>
void check_number_kind(const nlohmann::json& value, std::string_view kind, std::string_view key) {
    if constexpr (std::is_same_v<T, bool>) {
        if (!value.is_boolean())
            field_error(kind, key, std::string("expected true or false, got ") + value.type_name());
    } else if constexpr (std::is_unsigned_v<T>) {
        if (!value.is_number_unsigned()) field_error(kind, key, "expected a non-negative integer, got " + value.dump());
        if (value.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<T>::max()))
            field_error(kind, key, value.dump() + " is out of range");
    } else if constexpr (std::is_integral_v<T>) {
        if (!value.is_number_integer()) field_error(kind, key, "expected an integer, got " + value.dump());
    } else if constexpr (std::is_floating_point_v<T>) {
        if (!value.is_number()) field_error(kind, key, std::string("expected a number, got ") + value.type_name());
        // Converting a double beyond T's range is undefined behaviour, not infinity.
        const double number = value.get<double>();
        if (std::abs(number) > static_cast<double>(std::numeric_limits<T>::max()))
            field_error(kind, key, value.dump() + " is out of range");
    }
}

// Reads json[key] into `out` when present (absent keys keep their defaults). Conversion errors,
// including those thrown by nested from_json functions, are prefixed with kind.key.
template <class T>
void read(const nlohmann::json& json, std::string_view kind, const char* key, T& out) {
    const auto it = json.find(key);
    if (it == json.end()) return;
    check_number_kind<T>(*it, kind, key);
    try {
        it->get_to(out);
    } catch (const nlohmann::json::exception& e) {
        field_error(kind, key, e.what());
    } catch (const std::invalid_argument& e) {
        field_error(kind, key, e.what());
    }
}

// Enumerations travel as their names; `names` is indexed by the enumerator's value.
template <class E, std::size_t N>
std::string_view enum_name(const std::array<std::string_view, N>& names, E value) {
    const auto index = static_cast<std::size_t>(value);
    return index < N ? names[index] : std::string_view("<invalid>");
}

template <class E, std::size_t N>
E enum_from_json(const std::array<std::string_view, N>& names, const nlohmann::json& json) {
    std::string expected;
    for (const auto name : names) expected += (expected.empty() ? "" : ", ") + std::string(name);
    if (!json.is_string())
        throw std::invalid_argument("expected one of " + expected + " as a string, got " + json.dump());
    const auto& text = json.get_ref<const std::string&>();
    for (std::size_t i = 0; i < N; ++i)
        if (names[i] == text) return static_cast<E>(i);
    throw std::invalid_argument("unknown value '" + text + "' (expected one of: " + expected + ")");
}

}  // namespace plugin_msgs::detail
