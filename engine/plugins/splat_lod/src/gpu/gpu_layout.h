#pragma once
// C++ view of the splat pipeline's GPU contract, with the layout checks that keep C++ and GLSL
// in agreement (std430/std140 offsets of vec4/uvec4/mat4 members are 16-byte multiples).
#include <cstddef>

#include <splat_lod/splat_lod_shared.h>

namespace splat_lod::gpu {

static_assert(sizeof(GpuGaussian) == 64);
static_assert(offsetof(GpuGaussian, lod) == 48);
static_assert(sizeof(GpuInstance) == 144);
static_assert(offsetof(GpuInstance, info) == 128);
static_assert(sizeof(ProjectedSplat) == 64);
static_assert(offsetof(ProjectedSplat, tile_rect) == 48);
static_assert(sizeof(FrameUniforms) == 160);
static_assert(offsetof(FrameUniforms, tiles) == 144);
static_assert(sizeof(FrameCounters) == 32);
static_assert(offsetof(FrameCounters, per_level) == 16);

}  // namespace splat_lod::gpu
