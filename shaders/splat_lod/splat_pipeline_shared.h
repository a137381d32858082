// The splat frame pipeline's GPU contract (cull/project, bin, tile ranges, raster), compiled by
// C++ and GLSL: std430 struct layouts, binding indices, workgroup sizes. C++ checks sizes with
// static_assert in engine/plugins/splat_lod/src/gpu/gpu_layout.h. No bare vec3 members.
#ifndef SPLAT_PIPELINE_SHARED_H
#define SPLAT_PIPELINE_SHARED_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace splat_lod::gpu {
using uint = std::uint32_t;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
#endif

#define SPLAT_TILE_SIZE 16                 // pixels per tile side (the raster workgroup is one tile)
#define SPLAT_PROJECT_WORKGROUP_SIZE 256
#define SPLAT_BIN_WORKGROUP_SIZE 256
#define SPLAT_RANGES_WORKGROUP_SIZE 256
#define SPLAT_MAX_SH_DEGREE 3
#define SPLAT_MAX_LEVELS 4

// Shader storage bindings.
#define SPLAT_BINDING_GAUSSIANS 0      // GpuGaussian[N], static per cloud
#define SPLAT_BINDING_SH 1             // float[N * sh_stride], static per cloud
#define SPLAT_BINDING_INSTANCES 2      // GpuInstance[], per frame
#define SPLAT_BINDING_PROJECTED 3      // ProjectedSplat[N], per frame
#define SPLAT_BINDING_TILE_COUNTS 4    // uint[N + 1]: tiles touched; scanned in place into key offsets, total at [N]
#define SPLAT_BINDING_KEYS 5           // uvec2[capacity]: (depth bits, tile index)
#define SPLAT_BINDING_VALUES 6         // uint[capacity]: Gaussian index
#define SPLAT_BINDING_TILE_RANGES 7    // uvec2[tile_count]: [begin, end) into the sorted keys
#define SPLAT_BINDING_STATS 8          // FrameCounters
#define SPLAT_BINDING_ARGS 9           // uvec4: tile-range dispatch size (xyz) and keys in use (w)
#define SPLAT_UNIFORM_FRAME 0          // FrameUniforms (uniform block binding)
#define SPLAT_IMAGE_COLOR 0            // the frame's display-space colour (rgba8), read and written
#define SPLAT_TEXTURE_VIEW_DEPTH 1     // the mesh pass's view depth (r32f), +inf where no mesh

// Gaussians with their 3D covariance precomputed (local space of the cloud).
#ifdef __cplusplus
struct alignas(16) GpuGaussian {
#else
struct GpuGaussian {
#endif
    vec4 position_opacity;  // xyz local mean, w activated opacity
    vec4 covariance_a;      // Σ xx, xy, xz, yy
    vec4 covariance_b;      // Σ yz, zz, w = uintBitsToFloat(instance index)
    vec4 lod;               // x coverage_min, y coverage_max, z level (1..4), w unused
};

// One splat component this frame.
#ifdef __cplusplus
struct alignas(16) GpuInstance {
#else
struct GpuInstance {
#endif
    mat4 model;             // local → world
    mat4 rotation_inverse;  // world → local directions (for SH)
    uvec4 info;             // x first Gaussian, y count, z SH degree used, w unused
};

// A projected Gaussian, stored at its Gaussian index (entries of culled ones are not read).
#ifdef __cplusplus
struct alignas(16) ProjectedSplat {
#else
struct ProjectedSplat {
#endif
    vec4 mean_depth;  // x, y image position (top-left origin), z view depth, w opacity
    vec4 conic;       // inverse of the dilated 2D covariance: xx, xy, yy; w unused
    vec4 color;       // rgb (SH + 0.5, clamped at 0), w unused
    uvec4 tile_rect;  // tiles [x0, x1) × [y0, y1)
};

#ifdef __cplusplus
struct alignas(16) FrameUniforms {
#else
struct FrameUniforms {
#endif
    mat4 view;              // world → view
    vec4 camera_position;   // world, w unused
    vec4 focal_principal;   // fx, fy, cx, cy (pixels)
    vec4 image;             // width, height, 1.3·tan(fov_x/2), 1.3·tan(fov_y/2)
    vec4 params;            // znear, dilation, mip filter (0/1), unused
    uvec4 counts;           // Gaussian count, sh_stride (floats), key capacity, instance count
    uvec4 tiles;            // tiles_x, tiles_y, tile_count, unused
};

// Written by the GPU each frame and read back asynchronously by the CPU.
#ifdef __cplusplus
struct alignas(16) FrameCounters {
#else
struct FrameCounters {
#endif
    uint considered;
    uint visible;
    uint keys_needed;   // tile-splat pairs this frame asked for
    uint overflowed;    // 1 when keys_needed > key capacity (the frame dropped pairs)
    uvec4 per_level;    // visible Gaussians per LOD level 1..4
};

#ifdef __cplusplus
}  // namespace splat_lod::gpu
#endif

#endif  // SPLAT_PIPELINE_SHARED_H
