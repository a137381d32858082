// The engine's GPU sort and scan (engine/gl/radix_sort.h, engine/gl/prefix_scan.h), compiled by C++
// and GLSL alike: workgroup sizes, binding indices and the layouts of the buffers the GPU writes for
// them (std430). The programs are engine/radix_sort_*.comp.glsl and engine/prefix_scan_*.comp.glsl;
// a caller binds its own buffers at the caller-facing bindings (keys, values, count) and nothing else.
#ifndef ENGINE_GPU_SORT_SHARED_H
#define ENGINE_GPU_SORT_SHARED_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace engine::gl {
using uint = std::uint32_t;
using uvec4 = glm::uvec4;
#define ENGINE_GPU_STRUCT(name) struct alignas(16) name
#else
#define ENGINE_GPU_STRUCT(name) struct name
#endif

// Sizes measured on llvmpipe (process CPU time per 1M-key sort, hi_bits 12): the scatter reads
// SORT_WORKGROUP_SIZE / 32 mask words per element, so 64 invocations took 350 ms against 400 ms
// for 128 and 700 ms for 256; 4-bit digits (11 passes instead of 6) took 595 ms. Tiles of 2048
// keys balance per-tile overhead against the histogram length. Scans of 4M values ran ~3x
// faster with 16 elements per thread than with 4 (the workgroup scan is amortised).
#define SORT_WORKGROUP_SIZE 64
#define SORT_RADIX_BITS 8
#define SORT_RADIX_SIZE 256          // 1 << SORT_RADIX_BITS
#define SORT_ELEMENTS_PER_THREAD 32  // elements one thread handles in a sort pass
#define SCAN_WORKGROUP_SIZE 256
#define SCAN_ELEMENTS_PER_THREAD 16

// A sort tile is what one workgroup ranks: SORT_WORKGROUP_SIZE keys per round, in order.
#define SORT_TILE_SIZE (SORT_WORKGROUP_SIZE * SORT_ELEMENTS_PER_THREAD)
// The scatter ranks a round with one bit per invocation per digit: this many words per digit.
#define SORT_MASK_WORDS (SORT_WORKGROUP_SIZE / 32)
// Elements one scan workgroup reduces or scans; each level of block sums is this much shorter.
#define SCAN_BLOCK_SIZE (SCAN_WORKGROUP_SIZE * SCAN_ELEMENTS_PER_THREAD)
// Levels of block sums: the indirect dispatch limit (65535 groups) is reached before level 3.
#define SCAN_MAX_LEVELS 4

// Sort bindings (radix_sort_*.comp.glsl).
#define SORT_BINDING_KEYS_IN 0
#define SORT_BINDING_VALUES_IN 1
#define SORT_BINDING_KEYS_OUT 2
#define SORT_BINDING_VALUES_OUT 3
#define SORT_BINDING_HISTOGRAM 4  // per-tile digit counts, digit-major: [digit * tile_count + tile]
#define SORT_BINDING_PARAMS 5     // SortParams
#define SORT_BINDING_COUNT 6      // the caller's element count (radix_sort_dispatch_args only)
// Buffer textures over the sort's input keys (rg32ui) and values (r32ui) with SortJob::texel_reads;
// units of their own, above the splat pass's.
#define SORT_TEXTURE_KEYS_IN 14
#define SORT_TEXTURE_VALUES_IN 15

// Scan bindings (prefix_scan_*.comp.glsl).
#define SCAN_BINDING_DATA 0    // the level being reduced or scanned
#define SCAN_BINDING_SUMS 1    // block sums of the level (the next level's data)
#define SCAN_BINDING_LEVELS 2  // ScanLevel[SCAN_MAX_LEVELS]
#define SCAN_BINDING_COUNT 3   // the caller's element count (prefix_scan_dispatch_args only)
#define SCAN_BINDING_TOTAL 4   // where the top level writes the sum of all elements

// Written on the GPU from the element count by radix_sort_dispatch_args; `dispatch` is the
// glDispatchComputeIndirect argument (x = tile_count, y = z = 1) at byte offset 0.
ENGINE_GPU_STRUCT(SortParams) {
    uvec4 dispatch;
    uint count;            // min(caller's count, max_count)
    uint tile_count;       // ceil(count / SORT_TILE_SIZE)
    uint histogram_count;  // SORT_RADIX_SIZE * tile_count: the length of the scanned histogram
    uint histogram_total;  // written by the histogram scan (equals count)
};

// One scan level: x, y, z are its glDispatchComputeIndirect arguments (byte offset 16 * level).
ENGINE_GPU_STRUCT(ScanLevel) {
    uint groups_x;
    uint groups_y;
    uint groups_z;
    uint count;  // elements at this level
};

#ifdef __cplusplus
}  // namespace engine::gl
#endif

#endif
