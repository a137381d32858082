#pragma once
// The splat LOD settings (docs/algorithms.md §3 and §5): which Gaussians the selection
// rule keeps (Yan et al. Eq. 6; docs/algorithms.md names the papers), at which resolution splats are rasterised and how
// they are upscaled. The UI and tools publish it; the splat_lod plugin reads it.
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "plugin_msgs/detail/json_read.h"

namespace plugin_msgs {

// Ablation modes of Yan et al.'s Table 1.
enum class LodMode {
    baseline,      // level 1 only, no coverage filter
    filter_small,  // level 1 only, selection rule applied
    insert_large,  // all levels, no coverage filter
    full,          // all levels, selection rule applied
};
inline constexpr std::array<std::string_view, 4> kLodModeNames{"baseline", "filter_small", "insert_large", "full"};

// How a low-resolution splat image is brought to output size (Niedermayr et al.).
enum class Upscaler { spline, bicubic, bilinear, lanczos3 };
inline constexpr std::array<std::string_view, 4> kUpscalerNames{"spline", "bicubic", "bilinear", "lanczos3"};

inline std::string_view to_string(LodMode mode) {
    return detail::enum_name(kLodModeNames, mode);
}
inline std::string_view to_string(Upscaler upscaler) {
    return detail::enum_name(kUpscalerNames, upscaler);
}

inline void to_json(nlohmann::json& json, LodMode mode) {
    json = std::string(to_string(mode));
}
inline void from_json(const nlohmann::json& json, LodMode& mode) {
    mode = detail::enum_from_json<LodMode>(kLodModeNames, json);
}
inline void to_json(nlohmann::json& json, Upscaler upscaler) {
    json = std::string(to_string(upscaler));
}
inline void from_json(const nlohmann::json& json, Upscaler& upscaler) {
    upscaler = detail::enum_from_json<Upscaler>(kUpscalerNames, json);
}

struct LodSettings {
    static constexpr std::string_view kind = "lod_settings";

    LodMode mode = LodMode::full;
    float size_threshold_px = 2.0f;  // S_T: below this coverage a Gaussian is "small"
    float rel_min = 0.5f;            // S_rel_min: drawn while S / S_min ≥ rel_min
    float rel_max = 1.5f;            // S_rel_max: drawn while S / S_max ≤ rel_max
    float render_scale = 1.0f;       // splat raster resolution relative to the output, in (0, 1]
    Upscaler upscaler = Upscaler::spline;
    bool mip_filter = false;       // Mip-Splatting's 2D filter, the anti-aliasing baseline (§1)
    bool level_colouring = false;  // debug view: tint each Gaussian by its LOD level
    // At most this many Gaussians drawn per frame (0: no budget): above it the frame's LOD cut moves
    // to coarser levels (as if its size threshold and coverage ranges were larger), chosen on the GPU.
    std::uint32_t splat_budget = 0;
    // Smooth level transitions (docs/lod.md, "Transitions"): a Gaussian near a switching coverage of
    // the selection rule is drawn with its opacity scaled by a weight that ramps linearly in log2
    // coverage over this many octaves before the switch, so it fades out while its coarser
    // replacement fades in; none is drawn past its switch, so the band costs no extra fine Gaussians.
    // 0: the rule's hard on/off switching. Only in mode full.
    float transition_band = kDefaultTransitionBand;
    static constexpr float kDefaultTransitionBand = 0.0625f;
    static constexpr float kMaxTransitionBand = 4.0f;

    // Empty when the settings are usable, otherwise "lod_settings.<key>: <why>".
    std::string validate() const;

    friend bool operator==(const LodSettings&, const LodSettings&) = default;
};

namespace detail {
inline std::string lod_error(std::string_view key, const std::string& message) {
    return std::string(LodSettings::kind) + "." + std::string(key) + ": " + message;
}
inline std::string number_text(float value) {
    return nlohmann::json(value).dump();
}
}  // namespace detail

// The comparisons are written so that NaN fails every check.
inline std::string LodSettings::validate() const {
    using detail::lod_error;
    using detail::number_text;
    if (detail::enum_name(kLodModeNames, mode) == "<invalid>") return lod_error("mode", "invalid enumerator");
    if (detail::enum_name(kUpscalerNames, upscaler) == "<invalid>") return lod_error("upscaler", "invalid enumerator");
    if (!(size_threshold_px > 0.0f) || !std::isfinite(size_threshold_px))
        return lod_error("size_threshold_px", "must be a finite number > 0, got " + number_text(size_threshold_px));
    if (!(rel_max > 0.0f) || !std::isfinite(rel_max))
        return lod_error("rel_max", "must be a finite number > 0, got " + number_text(rel_max));
    if (!(rel_min > 0.0f && rel_min <= rel_max))
        return lod_error("rel_min",
                         "must be in (0, rel_max = " + number_text(rel_max) + "], got " + number_text(rel_min));
    if (!(render_scale > 0.0f && render_scale <= 1.0f))
        return lod_error("render_scale", "must be in (0, 1], got " + number_text(render_scale));
    if (!(transition_band >= 0.0f && transition_band <= kMaxTransitionBand))
        return lod_error("transition_band", "must be in [0, " + number_text(kMaxTransitionBand) +
                                                "] octaves of coverage, got " + number_text(transition_band));
    return {};
}

inline void to_json(nlohmann::json& json, const LodSettings& s) {
    json = nlohmann::json{{"mode", s.mode},
                          {"size_threshold_px", s.size_threshold_px},
                          {"rel_min", s.rel_min},
                          {"rel_max", s.rel_max},
                          {"render_scale", s.render_scale},
                          {"upscaler", s.upscaler},
                          {"mip_filter", s.mip_filter},
                          {"level_colouring", s.level_colouring},
                          {"splat_budget", s.splat_budget},
                          {"transition_band", s.transition_band}};
}

// Missing keys keep their defaults; unknown keys, wrong types, unknown enum names and values
// outside their range throw std::invalid_argument naming the key.
inline void from_json(const nlohmann::json& json, LodSettings& s) {
    constexpr auto kind = LodSettings::kind;
    detail::require_object(json, kind);
    detail::only_keys(json, kind,
                      {"mode", "size_threshold_px", "rel_min", "rel_max", "render_scale", "upscaler", "mip_filter",
                       "level_colouring", "splat_budget", "transition_band"});
    LodSettings read;
    detail::read(json, kind, "mode", read.mode);
    detail::read(json, kind, "size_threshold_px", read.size_threshold_px);
    detail::read(json, kind, "rel_min", read.rel_min);
    detail::read(json, kind, "rel_max", read.rel_max);
    detail::read(json, kind, "render_scale", read.render_scale);
    detail::read(json, kind, "upscaler", read.upscaler);
    detail::read(json, kind, "mip_filter", read.mip_filter);
    detail::read(json, kind, "level_colouring", read.level_colouring);
    detail::read(json, kind, "splat_budget", read.splat_budget);
    detail::read(json, kind, "transition_band", read.transition_band);
    if (const std::string error = read.validate(); !error.empty()) throw std::invalid_argument(error);
    s = read;
}

}  // namespace plugin_msgs
