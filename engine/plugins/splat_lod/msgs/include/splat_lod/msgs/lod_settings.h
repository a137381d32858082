#pragma once
// The splat LOD settings (docs/algorithms.md §3 and §5): the selection rule (lod_rule.h), at which
// resolution splats are rasterised and how they are upscaled, and the per-frame splat budget. The
// UI and tools publish it; the splat pass takes the latest one whole (its only way in), and a chunk
// streamer with a bus takes the rule from it.
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "plugin_msgs/detail/json_read.h"
#include "splat_lod/msgs/lod_rule.h"

namespace plugin_msgs {

// How a low-resolution splat image is brought to output size (Niedermayr et al.).
enum class Upscaler { spline, bicubic, bilinear, lanczos3 };
inline constexpr std::array<std::string_view, 4> kUpscalerNames{"spline", "bicubic", "bilinear", "lanczos3"};

inline std::string_view to_string(Upscaler upscaler) {
    return detail::enum_name(kUpscalerNames, upscaler);
}
inline void to_json(nlohmann::json& json, Upscaler upscaler) {
    json = std::string(to_string(upscaler));
}
inline void from_json(const nlohmann::json& json, Upscaler& upscaler) {
    upscaler = detail::enum_from_json<Upscaler>(kUpscalerNames, json);
}

struct LodSettings {
    static constexpr std::string_view kind = "lod_settings";

    LodRule rule;               // which Gaussians are drawn (its keys sit flat in the JSON)
    float render_scale = 1.0f;  // splat raster resolution relative to the output, in (0, 1]
    Upscaler upscaler = Upscaler::spline;
    bool mip_filter = false;       // Mip-Splatting's 2D filter, the anti-aliasing baseline (§1)
    bool level_colouring = false;  // debug view: tint each Gaussian by its LOD level
    // At most this many Gaussians drawn per frame (0: no budget): above it the frame's LOD cut moves
    // to coarser levels (as if its size threshold and coverage ranges were larger), chosen on the GPU.
    std::uint32_t splat_budget = 0;

    // Empty when the settings are usable, otherwise "lod_settings.<key>: <why>".
    std::string validate() const;

    friend bool operator==(const LodSettings&, const LodSettings&) = default;
};

// The comparisons are written so that NaN fails every check.
inline std::string LodSettings::validate() const {
    if (std::string error = rule.validate(kind); !error.empty()) return error;
    if (detail::enum_name(kUpscalerNames, upscaler) == "<invalid>")
        return detail::rule_error(kind, "upscaler", "invalid enumerator");
    if (!(render_scale > 0.0f && render_scale <= 1.0f))
        return detail::rule_error(kind, "render_scale", "must be in (0, 1], got " + detail::number_text(render_scale));
    return {};
}

inline void to_json(nlohmann::json& json, const LodSettings& s) {
    json = nlohmann::json{{"render_scale", s.render_scale},
                          {"upscaler", s.upscaler},
                          {"mip_filter", s.mip_filter},
                          {"level_colouring", s.level_colouring},
                          {"splat_budget", s.splat_budget}};
    write_rule(json, s.rule);
}

// Missing keys keep their defaults; unknown keys, wrong types, unknown enum names and values
// outside their range throw std::invalid_argument naming the key.
inline void from_json(const nlohmann::json& json, LodSettings& s) {
    constexpr auto kind = LodSettings::kind;
    detail::require_object(json, kind);
    detail::only_keys(
        json, kind,
        {"mode", "size_threshold_px", "rel_min", "rel_max", "render_scale", "upscaler", "mip_filter", "level_colouring",
         "splat_budget", "transition_band", "transition_placement", "overlap_transition_band"});
    LodSettings read;
    read_rule(json, kind, read.rule);
    detail::read(json, kind, "render_scale", read.render_scale);
    detail::read(json, kind, "upscaler", read.upscaler);
    detail::read(json, kind, "mip_filter", read.mip_filter);
    detail::read(json, kind, "level_colouring", read.level_colouring);
    detail::read(json, kind, "splat_budget", read.splat_budget);
    if (const std::string error = read.validate(); !error.empty()) throw std::invalid_argument(error);
    s = read;
}

}  // namespace plugin_msgs
