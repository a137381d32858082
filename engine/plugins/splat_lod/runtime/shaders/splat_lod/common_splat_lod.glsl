// Pixel coverage and the LOD selection rule, the GLSL twin of splat_lod/core/lod_selection.h (the
// tests compare them Gaussian for Gaussian). Needs `frame` (FrameUniforms).

// docs/algorithms.md §2: S = 2·min(sqrt(L/Σ⁻¹ₓₓ), sqrt(L/Σ⁻¹ᵧᵧ)), L = 2·ln(255·o), undilated Σ2D.
float pixel_coverage(mat2 cov, float det, float opacity) {
    if (!(opacity > 1.0 / 255.0) || !(det > 0.0) || !(cov[0][0] > 0.0) || !(cov[1][1] > 0.0)) return 0.0;
    float level_set = 2.0 * log(255.0 * opacity);
    return 2.0 * min(sqrt(level_set * det / cov[1][1]), sqrt(level_set * det / cov[0][0]));
}

// docs/algorithms.md §3 (Yan et al. Eq. 6); bounds of −1 are unset.
bool lod_selected(uint level, float coverage, float coverage_min, float coverage_max) {
    uint finest = frame.finest_level, coarsest = frame.coarsest_level;
    bool all_levels = (frame.lod_flags & SPLAT_LOD_ALL_LEVELS) != 0u;
    if (!all_levels && level != finest) return false;
    if ((frame.lod_flags & SPLAT_LOD_COVERAGE_RULE) == 0u) return true;
    bool not_too_large = level == finest || coverage_max < 0.0 || coverage / coverage_max <= frame.rel_max;
    bool not_too_small = level == coarsest || coverage_min < 0.0 || coverage >= frame.size_threshold ||
                         coverage / coverage_min >= frame.rel_min;
    return not_too_large && not_too_small;
}

// The fade of an instance's Gaussians (GpuInstance::info.z): x the band in octaves, y and z the shifts
// of its "too small" and "too large" ramps (FrameUniforms::transitions).
vec3 instance_transition(uint info_z) {
    return frame.transitions[min((info_z & SPLAT_INSTANCE_HANDOVER_MASK) >> SPLAT_INSTANCE_HANDOVER_SHIFT, 2u)].xyz;
}

bool smooth_transitions(vec3 transition) {
    const uint both = SPLAT_LOD_COVERAGE_RULE | SPLAT_LOD_TRANSITIONS;
    return (frame.lod_flags & both) == both && transition.x > 0.0;
}

// The rule's two tests as log2 distances from their switches (> 0: the test fails by that many
// octaves for "large", holds by that many for "small"); ±1e30 where a test does not apply.
vec2 lod_switch_octaves(uint level, float coverage, float coverage_min, float coverage_max) {
    float x = -1e30, y = 1e30;
    if (level != frame.finest_level && coverage_max >= 0.0) x = log2(coverage / (coverage_max * frame.rel_max));
    if (level != frame.coarsest_level && coverage_min >= 0.0)
        y = log2(max(coverage / frame.size_threshold, coverage / (coverage_min * frame.rel_min)));
    return vec2(x, y);
}

// The opacity weight of lod_weight in splat_lod/core/lod_selection.h: linear ramps in log2 coverage,
// transition.x octaves wide, the "too small" one lying transition.y and the "too large" one transition.z
// octaves past its switch toward the coarser side (instance_transition); 0/1 by lod_selected when
// transitions are hard.
float lod_weight(uint level, float coverage, float coverage_min, float coverage_max, vec3 transition) {
    if (!smooth_transitions(transition) || !(coverage > 0.0))
        return lod_selected(level, coverage, coverage_min, coverage_max) ? 1.0 : 0.0;
    vec2 o = lod_switch_octaves(level, coverage, coverage_min, coverage_max);
    float band = transition.x;
    return clamp(1.0 - (o.x + transition.z) / band, 0.0, 1.0) * clamp((o.y + transition.y) / band, 0.0, 1.0);
}

// Debug view: each level tinted (1 grey, 2 green, 3 blue, 4 red), keeping the shading's brightness.
vec3 level_colour(uint level, vec3 colour) {
    const vec3 tint[4] = vec3[](vec3(0.8), vec3(0.2, 0.9, 0.2), vec3(0.25, 0.45, 1.0), vec3(1.0, 0.25, 0.2));
    float brightness = dot(colour, vec3(0.299, 0.587, 0.114));
    return tint[level - 1u] * (0.35 + 0.65 * clamp(brightness, 0.0, 1.0));
}

// The splat budget (splat_lod_shared.h): the β bins [x, y] in which the Gaussian is selected (a weight
// above 0) with its coverage divided by β = 2^(b/8); empty when y < x. Bin 0 (β = 1) agrees with
// lod_weight > 0, so a budget that does not bind changes nothing. "Not too large" holds from
// log2 β > x − b + s_large on, "not too small" up to log2 β < y + s_small, with x, y of
// lod_switch_octaves, b the transition band and s the ramps' shifts (all 0 when transitions are hard:
// then the bounds are inclusive, as in lod_selected).
ivec2 budget_bins(uint level, float coverage, float coverage_min, float coverage_max, vec3 transition) {
    const ivec2 none = ivec2(1, 0);
    bool all_levels = (frame.lod_flags & SPLAT_LOD_ALL_LEVELS) != 0u;
    if (!all_levels && level != frame.finest_level) return none;
    if ((frame.lod_flags & SPLAT_LOD_COVERAGE_RULE) == 0u) return ivec2(0, SPLAT_BUDGET_BINS - 1);
    if (!(coverage > 0.0)) return lod_selected(level, coverage, coverage_min, coverage_max) ? ivec2(0) : none;
    vec2 o = lod_switch_octaves(level, coverage, coverage_min, coverage_max);
    bool smooth_fade = smooth_transitions(transition);
    float b = smooth_fade ? transition.x : 0.0;
    vec2 shift = smooth_fade ? transition.yz : vec2(0.0);
    // With a ramp the weight is 0 exactly at x = b − s_large and y = −s_small, so those bounds are
    // exclusive: nudged by a hair.
    float lo_octaves = o.x - b + shift.y + (smooth_fade ? 1e-6 : 0.0);
    float hi_octaves = o.y + shift.x - (smooth_fade ? 1e-6 : 0.0);
    if (hi_octaves < 0.0) return none;
    int lo = lo_octaves <= 0.0 ? 0 : int(clamp(ceil(SPLAT_BUDGET_BINS_PER_OCTAVE * lo_octaves), 1.0, float(SPLAT_BUDGET_BINS)));
    int hi = int(clamp(floor(SPLAT_BUDGET_BINS_PER_OCTAVE * hi_octaves), 0.0, float(SPLAT_BUDGET_BINS - 1)));
    return ivec2(lo, hi);
}

// The coverage histogram's bin of a coverage in px (splat_lod_shared.h).
uint coverage_bin(float coverage) {
    float k = floor(SPLAT_BUDGET_BINS_PER_OCTAVE * log2(max(coverage, 1e-30)) + SPLAT_COVERAGE_BIN_OFFSET);
    return uint(clamp(k, 0.0, float(SPLAT_COVERAGE_BINS - 1)));
}
