#pragma once
// C++ view of the splat pipeline's GPU contract, with the layout checks that keep C++ and GLSL
// in agreement (std430/std140 offsets of vec4/uvec4/mat4 members are 16-byte multiples).
#include <cstddef>
#include <cstdint>

#include <splat_lod/splat_lod_shared.h>
#include "splat_lod/core/compact_gaussians.h"
#include "splat_lod/core/lod_selection.h"
#include "splat_lod/msgs/lod_settings.h"

namespace splat_lod::gpu {

static_assert(sizeof(GpuGaussian) == 64);
static_assert(offsetof(GpuGaussian, lod) == 48);
static_assert(sizeof(GpuInstance) == 144);
static_assert(offsetof(GpuInstance, info) == 128);
static_assert(sizeof(GpuCluster) == 48);
static_assert(sizeof(GpuPageCodec) == 80);
static_assert(SPLAT_COMPACT_WORDS == kCompactWords && SPLAT_PROJECT_WORKGROUP_SIZE == kCompactPageSize);
static_assert(sizeof(ProjectedSplat) == 48);
static_assert(sizeof(FrameUniforms) == 352);
static_assert(sizeof(FrameUniforms::transitions) / sizeof(FrameUniforms::transitions[0]) ==
              plugin_msgs::kLevelHandoverCount);
static_assert((static_cast<std::uint32_t>(plugin_msgs::kLevelHandoverCount - 1) << SPLAT_INSTANCE_HANDOVER_SHIFT &
               ~SPLAT_INSTANCE_HANDOVER_MASK) == 0u);
// std140 offsets of every FrameUniforms member.
static_assert(offsetof(FrameUniforms, camera_position) == 64);
static_assert(offsetof(FrameUniforms, znear) == 76);
static_assert(offsetof(FrameUniforms, focal) == 80);
static_assert(offsetof(FrameUniforms, principal) == 88);
static_assert(offsetof(FrameUniforms, raster_size) == 96);
static_assert(offsetof(FrameUniforms, jacobian_clamp) == 104);
static_assert(offsetof(FrameUniforms, dilation) == 112);
static_assert(offsetof(FrameUniforms, gaussian_count) == 128);
static_assert(offsetof(FrameUniforms, tiles) == 144);
static_assert(offsetof(FrameUniforms, tile_count) == 152);
static_assert(offsetof(FrameUniforms, size_threshold) == 160);
static_assert(offsetof(FrameUniforms, lod_flags) == 176);
static_assert(offsetof(FrameUniforms, output_size) == 192);
static_assert(offsetof(FrameUniforms, render_scale) == 200);
static_assert(offsetof(FrameUniforms, splat_budget) == 208);
static_assert(offsetof(FrameUniforms, exact_tiles) == 216);
static_assert(offsetof(FrameUniforms, key_depth_bits) == 220);
static_assert(offsetof(FrameUniforms, splat_capacity) == 224);
static_assert(offsetof(FrameUniforms, selection_view) == 240);
static_assert(offsetof(FrameUniforms, transitions) == 304);
static_assert(sizeof(FrameCounters) == 80);
static_assert(offsetof(FrameCounters, depth_range) == 64);
static_assert(offsetof(FrameCounters, budget) == 48);
static_assert(sizeof(SplatBudgetState) == 16 + 4 * (SPLAT_BUDGET_BINS + SPLAT_COVERAGE_BINS));
static_assert(offsetof(FrameCounters, per_level) == 16);

// The LOD rule's one conversion into the frame uniforms: its thresholds, and its mode as the flags of
// the mode's traits (the shaders read the flags, never the mode).
constexpr std::uint32_t lod_flags(plugin_msgs::LodModeTraits mode) {
    return (mode.all_levels ? SPLAT_LOD_ALL_LEVELS : 0u) | (mode.coverage_rule ? SPLAT_LOD_COVERAGE_RULE : 0u) |
           (mode.transitions ? SPLAT_LOD_TRANSITIONS : 0u);
}
inline void write_lod_rule(FrameUniforms& u, const plugin_msgs::LodRule& rule) {
    u.size_threshold = rule.size_threshold_px;
    u.rel_min = rule.rel_min;
    u.rel_max = rule.rel_max;
    u.lod_flags = lod_flags(plugin_msgs::traits(rule.mode));
    u.finest_level = static_cast<std::uint32_t>(kFinestLevel);
    // Per asset kind (FrameUniforms::transitions); 0 without transitions, so that skipping keeps the
    // hard rule's thresholds there.
    for (int kind = 0; kind < plugin_msgs::kLevelHandoverCount; ++kind) {
        const plugin_msgs::LodRule asset = rule.for_asset(static_cast<plugin_msgs::LevelHandover>(kind));
        const plugin_msgs::TransitionShifts shifts =
            plugin_msgs::transition_shifts(asset.transition_placement, asset.transition_band);
        u.transitions[kind] = plugin_msgs::traits(rule.mode).transitions
                                  ? glm::vec4(asset.transition_band, shifts.small, shifts.large, 0.0f)
                                  : glm::vec4(0.0f);
    }
}

static_assert(static_cast<int>(plugin_msgs::Upscaler::spline) == SPLAT_UPSCALER_SPLINE);
static_assert(static_cast<int>(plugin_msgs::Upscaler::bicubic) == SPLAT_UPSCALER_BICUBIC);
static_assert(static_cast<int>(plugin_msgs::Upscaler::bilinear) == SPLAT_UPSCALER_BILINEAR);
static_assert(static_cast<int>(plugin_msgs::Upscaler::lanczos3) == SPLAT_UPSCALER_LANCZOS3);

}  // namespace splat_lod::gpu
