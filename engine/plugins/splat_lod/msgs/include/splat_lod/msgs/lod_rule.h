#pragma once
// The LOD selection rule (docs/algorithms.md §3): which Gaussians a view draws, by their pixel
// coverage. This is the one definition of the rule's parameters and of their defaults; the bake,
// the splat pass (through one conversion into its frame uniforms), the chunk streamer and the
// evaluation all take this type. The rule itself is evaluated by splat_lod/core/lod_selection.h on
// the CPU and its GLSL twin on the GPU; both ask `traits(mode)` what a mode does and never compare
// modes, so a mode that combines existing behaviours is added here alone.
#include <array>
#include <cmath>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "plugin_msgs/detail/json_read.h"
#include "splat_lod/msgs/level_handover.h"

namespace plugin_msgs {

// The ablation modes of the multi-scale method (its Table 1), and full_hard: full with hard on/off
// switching at the rule's thresholds whatever the band (to compare with the transitions, or where a
// frame must not blend two levels).
enum class LodMode {
    baseline,      // level 1 only, no coverage filter
    filter_small,  // level 1 only, selection rule applied
    insert_large,  // all levels, no coverage filter
    full,          // all levels, selection rule applied, smooth transitions
    full_hard,     // all levels, selection rule applied, hard switching
};
inline constexpr std::array<std::string_view, 5> kLodModeNames{"baseline", "filter_small", "insert_large", "full",
                                                               "full_hard"};

// What a mode does. Every consumer of the rule reads these, so they are the only place modes differ.
struct LodModeTraits {
    bool all_levels = false;     // every bake level takes part (else only the finest, level 1)
    bool coverage_rule = false;  // the coverage tests of the rule apply (else every candidate is drawn)
    bool transitions = false;    // transition_band > 0 fades Gaussians at the rule's switches
};

constexpr LodModeTraits traits(LodMode mode) {
    switch (mode) {
        case LodMode::baseline:
            return {false, false, false};
        case LodMode::filter_small:
            return {false, true, false};
        case LodMode::insert_large:
            return {true, false, false};
        case LodMode::full:
            return {true, true, true};
        case LodMode::full_hard:
            return {true, true, false};
    }
    return {};
}

inline std::string_view to_string(LodMode mode) {
    return detail::enum_name(kLodModeNames, mode);
}
inline void to_json(nlohmann::json& json, LodMode mode) {
    json = std::string(to_string(mode));
}
inline void from_json(const nlohmann::json& json, LodMode& mode) {
    mode = detail::enum_from_json<LodMode>(kLodModeNames, json);
}

// Where each Gaussian's fade lies against its switch (docs/algorithms.md §3, "Smooth transitions").
enum class TransitionPlacement {
    inside,     // within the range where the hard rule draws it: a fine Gaussian fades out over the band
                // before its "too small" switch, a coarse one fades in over the band past its "too large"
                // switch; nothing is drawn that the hard rule does not draw, and a hand-over at one
                // coverage dips (docs/lod.md, "Transitions": better on orbit captures, worse on forward ones)
    before,     // both on the finer side: a coarse Gaussian fades in over the band before its "too large"
                // switch (drawn where the hard rule does not yet draw it), so a hand-over at one coverage
                // sums to 1
    centred,    // both centred on their switch: a hand-over sums to 1, and a fine Gaussian is drawn past
                // its "too small" switch
    staggered,  // a coarse Gaussian fades in as `inside`, a fine one fades out centred on its "too small"
                // switch: where the levels' ranges overlap, the fine one's fade begins half a band later
                // than `inside`'s, so the two fades thin the double cover less (docs/lod.md, "Transitions")
    automatic,  // "auto", the default: per asset, by how its levels hand over (LevelHandover):
                // `inside` with overlap_transition_band where its bake left the levels' ranges
                // overlapping, `centred` with transition_band where it made them abut, `before` with
                // transition_band where nothing says (a streamed world's chunks and groups)
};
inline constexpr std::array<std::string_view, 5> kTransitionPlacementNames{"inside", "before", "centred", "staggered",
                                                                           "auto"};

inline std::string_view to_string(TransitionPlacement placement) {
    return detail::enum_name(kTransitionPlacementNames, placement);
}
inline void to_json(nlohmann::json& json, TransitionPlacement placement) {
    json = std::string(to_string(placement));
}
inline void from_json(const nlohmann::json& json, TransitionPlacement& placement) {
    placement = detail::enum_from_json<TransitionPlacement>(kTransitionPlacementNames, json);
}

// How far each of the two ramps lies past its switch, toward the coarser side, in octaves of coverage:
// `small` for a Gaussian's "too small" fade-out, `large` for its "too large" fade-in.
struct TransitionShifts {
    float small = 0.0f, large = 0.0f;
};
constexpr TransitionShifts transition_shifts(TransitionPlacement placement, float band) {
    switch (placement) {
        case TransitionPlacement::inside:
            return {0.0f, band};
        case TransitionPlacement::before:
        case TransitionPlacement::automatic:  // unresolved (LodRule::for_asset): as for an unknown handover
            return {0.0f, 0.0f};
        case TransitionPlacement::centred:
            return {0.5f * band, 0.5f * band};
        case TransitionPlacement::staggered:
            return {0.5f * band, band};
    }
    return {};
}

struct LodRule {
    LodMode mode = LodMode::full;
    float size_threshold_px = 2.0f;  // S_T: below this coverage a Gaussian is "small"
    float rel_min = 0.5f;            // S_rel_min: drawn while S / S_min ≥ rel_min
    float rel_max = 1.5f;            // S_rel_max: drawn while S / S_max ≤ rel_max
    // Smooth level transitions (docs/lod.md, "Transitions"): a Gaussian near a switching coverage of
    // the rule is drawn with its opacity scaled by a weight that ramps linearly in log2 coverage over
    // this many octaves; transition_placement says on which side of the switch. 0: hard switching.
    // Only in modes whose traits have transitions.
    float transition_band = kDefaultTransitionBand;
    static constexpr float kDefaultTransitionBand = 0.375f;
    static constexpr float kMaxTransitionBand = 4.0f;
    TransitionPlacement transition_placement = TransitionPlacement::automatic;
    // The band of an asset whose levels overlap at their switches, under the placement `auto` (placed
    // `inside` there; docs/lod.md, "Transitions", has how it was chosen).
    float overlap_transition_band = kDefaultOverlapTransitionBand;
    static constexpr float kDefaultOverlapTransitionBand = 0.5f;

    // The rule one asset is drawn with: under `auto` its placement and band resolved by how the
    // asset's levels hand over (`inside` with overlap_transition_band where they overlap, `centred` with
    // transition_band where they abut, `before` with transition_band where it is unknown); any other
    // placement is the rule itself.
    LodRule for_asset(LevelHandover handover) const;

    // Empty when the rule is usable, otherwise "<kind>.<key>: <why>". NaN fails every check.
    std::string validate(std::string_view kind = "lod_rule") const;

    friend bool operator==(const LodRule&, const LodRule&) = default;
};

namespace detail {
inline std::string rule_error(std::string_view kind, std::string_view key, const std::string& message) {
    return std::string(kind) + "." + std::string(key) + ": " + message;
}
inline std::string number_text(float value) {
    return nlohmann::json(value).dump();
}
}  // namespace detail

inline std::string LodRule::validate(std::string_view kind) const {
    using detail::number_text;
    const auto error = [kind](std::string_view key, const std::string& message) {
        return detail::rule_error(kind, key, message);
    };
    if (detail::enum_name(kLodModeNames, mode) == "<invalid>") return error("mode", "invalid enumerator");
    if (!(size_threshold_px > 0.0f) || !std::isfinite(size_threshold_px))
        return error("size_threshold_px", "must be a finite number > 0, got " + number_text(size_threshold_px));
    if (!(rel_max > 0.0f) || !std::isfinite(rel_max))
        return error("rel_max", "must be a finite number > 0, got " + number_text(rel_max));
    if (!(rel_min > 0.0f && rel_min <= rel_max))
        return error("rel_min", "must be in (0, rel_max = " + number_text(rel_max) + "], got " + number_text(rel_min));
    if (!(transition_band >= 0.0f && transition_band <= kMaxTransitionBand))
        return error("transition_band", "must be in [0, " + number_text(kMaxTransitionBand) +
                                            "] octaves of coverage, got " + number_text(transition_band));
    if (!(overlap_transition_band >= 0.0f && overlap_transition_band <= kMaxTransitionBand))
        return error("overlap_transition_band", "must be in [0, " + number_text(kMaxTransitionBand) +
                                                    "] octaves of coverage, got " +
                                                    number_text(overlap_transition_band));
    if (detail::enum_name(kTransitionPlacementNames, transition_placement) == "<invalid>")
        return error("transition_placement", "invalid enumerator");
    return {};
}

inline LodRule LodRule::for_asset(LevelHandover handover) const {
    if (transition_placement != TransitionPlacement::automatic) return *this;
    LodRule rule = *this;
    switch (handover) {
        case LevelHandover::overlapping:
            rule.transition_placement = TransitionPlacement::inside;
            rule.transition_band = overlap_transition_band;
            break;
        case LevelHandover::abutting:
            rule.transition_placement = TransitionPlacement::centred;
            break;
        case LevelHandover::unknown:
            rule.transition_placement = TransitionPlacement::before;
            break;
    }
    return rule;
}

// The rule's keys, written into (and read from) the object of whatever carries it: a LodSettings
// message, a world manifest. Reading leaves missing keys as they are and does not validate.
inline void write_rule(nlohmann::json& object, const LodRule& rule) {
    object["mode"] = rule.mode;
    object["size_threshold_px"] = rule.size_threshold_px;
    object["rel_min"] = rule.rel_min;
    object["rel_max"] = rule.rel_max;
    object["transition_band"] = rule.transition_band;
    object["transition_placement"] = rule.transition_placement;
    object["overlap_transition_band"] = rule.overlap_transition_band;
}
inline void read_rule(const nlohmann::json& object, std::string_view kind, LodRule& rule) {
    detail::read(object, kind, "mode", rule.mode);
    detail::read(object, kind, "size_threshold_px", rule.size_threshold_px);
    detail::read(object, kind, "rel_min", rule.rel_min);
    detail::read(object, kind, "rel_max", rule.rel_max);
    detail::read(object, kind, "transition_band", rule.transition_band);
    detail::read(object, kind, "transition_placement", rule.transition_placement);
    detail::read(object, kind, "overlap_transition_band", rule.overlap_transition_band);
}

}  // namespace plugin_msgs
