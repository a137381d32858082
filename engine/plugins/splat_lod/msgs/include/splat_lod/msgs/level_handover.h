#pragma once
// How a baked asset's levels hand over from one to the next, which decides where its fades lie under
// the transition placement `auto` (LodRule::for_asset in splat_lod/msgs/lod_rule.h; docs/lod.md,
// "Transitions", "Per asset"). Here so that the rule can name it without the CPU cloud.
namespace plugin_msgs {

// `overlapping`: the bake left the ranges of consecutive levels overlapping (a fine Gaussian and its
// coarser replacement are both drawn over a range of distances; splat_bake without member ranges, the
// orbit recipe). `abutting`: the bake capped them to meet at one coverage (member ranges, the
// forward-capture recipe). `unknown`: nothing says, such as a streamed world's chunks and groups (whose
// detail gives way to coarser detail where the cut switches a chunk for its group) and files baked
// before the handover was recorded. The values index FrameUniforms::transitions.
enum class LevelHandover { unknown, overlapping, abutting };
inline constexpr int kLevelHandoverCount = 3;

}  // namespace plugin_msgs
