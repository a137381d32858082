// The splat_lod GPU contract, compiled by C++ and GLSL alike: struct layouts (std430), binding
// indices and workgroup sizes. C++ checks sizes and offsets with static_assert
// (engine/plugins/splat_lod/runtime/src/gpu/gpu_layout.h); GLSL includes this file directly.
// Rule: no bare vec3 members in std430 structs (use vec4 or explicit padding).
#ifndef SPLAT_LOD_SHARED_H
#define SPLAT_LOD_SHARED_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace splat_lod::gpu {
using uint = std::uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
#define SPLAT_LOD_STRUCT(name) struct alignas(16) name
#else
#define SPLAT_LOD_STRUCT(name) struct name
#endif

// ---- The frame pipeline: cull/project, bin, tile ranges, raster (splat_lod/splat_*.comp.glsl) ----
#define SPLAT_TILE_SIZE 16  // pixels per tile side (the raster workgroup is one tile)
#define SPLAT_PROJECT_WORKGROUP_SIZE 256
#define SPLAT_CLUSTER_WORKGROUP_SIZE 64
#define SPLAT_RANGES_WORKGROUP_SIZE 256
#define SPLAT_MAX_SH_DEGREE 3
#define SPLAT_MAX_LEVELS 4
// FrameUniforms::lod_flags: what the LOD mode does (plugin_msgs::LodModeTraits); shaders read
// these, never the mode.
#define SPLAT_LOD_ALL_LEVELS 1u     // every bake level takes part (else only the finest)
#define SPLAT_LOD_COVERAGE_RULE 2u  // the coverage tests apply (else every candidate is drawn)
#define SPLAT_LOD_TRANSITIONS 4u    // transition_band > 0 fades Gaussians at the rule's switches

// Shader storage bindings.
// The scene's Gaussians and SH in one of two storages (GpuStorage, splat_lod/gpu_storage.h): full,
// GpuGaussian[N] and float[N * sh_stride]; compact (SPLAT_COMPACT_STORAGE), uint[N * 5], 20-byte records,
// and uint[N * sh_stride], the higher SH bands in 2 or 4 words, decoded against the
// GpuPageCodec of their page (splat_lod/core/compact_gaussians.h). Static per cloud.
#define SPLAT_BINDING_GAUSSIANS 0
#define SPLAT_BINDING_SH 1
#define SPLAT_BINDING_INSTANCES 2  // GpuInstance[], per frame
// The frame's splats are packed densely: each cluster step 1b projects (one per project workgroup)
// reserves one run of the array for its visible splats with a single atomic, so the runs' order depends
// on scheduling, and writes them in its Gaussians' order. The pairs stay deterministic: their positions
// come from a scan over the clusters in cluster order (SPLAT_BINDING_CLUSTER_PAIRS), and within a
// cluster from its splats' order. The arrays are sized by what the view draws (docs/gpu_storage.md).
#define SPLAT_BINDING_PROJECTED 3  // ProjectedSplat[frame.splat_capacity], per frame
// uint[C + 1], C = ceil(N / SPLAT_PROJECT_WORKGROUP_SIZE): the tile-splat pairs of each cluster's
// splats (0 for clusters not projected), scanned in place into each cluster's first key; total at [C].
#define SPLAT_BINDING_CLUSTER_PAIRS 4
#define SPLAT_BINDING_KEYS 5         // uvec2[capacity] (depth bits, tile), or uint[] one-word keys
#define SPLAT_BINDING_VALUES 6       // uint[capacity]: the splat's index in SPLAT_BINDING_PROJECTED
#define SPLAT_BINDING_TILE_RANGES 7  // uvec2[tile_count]: [begin, end) into the sorted keys
#define SPLAT_BINDING_STATS 8        // FrameCounters
#define SPLAT_BINDING_ARGS 9         // uvec4: tile-range dispatch size (xyz) and keys in use (w)
#define SPLAT_BINDING_CLUSTERS 10    // GpuCluster[ceil(N / SPLAT_PROJECT_WORKGROUP_SIZE)], static per scene
#define SPLAT_BINDING_CLUSTER_LIST \
    11                                // { uvec4 dispatch; uint ids[]; }: the clusters step 1b projects;
                                      // dispatch = its indirect arguments (x = clusters kept; the
                                      // CPU resets it to (0, 1, 1) each frame)
#define SPLAT_BINDING_BUDGET 12       // SplatBudgetState: the splat budget's histograms and choice, per frame
#define SPLAT_BINDING_PAGE_CODECS 13  // GpuPageCodec[pages], compact storage only, static per scene
// uvec2[C]: per projected cluster, its first splat in SPLAT_BINDING_PROJECTED and how many it wrote
// there (0 when they did not fit: the CPU then grows the array and runs steps 1 and 2 again).
#define SPLAT_BINDING_CLUSTER_SPLATS 14
#define SPLAT_BINDING_PICKS 15  // SplatPicks: the pixels picked this frame and their answers
// uint[C], in strips (SplatPassSettings::frame_memory_limit): per cluster, 0 until a strip projects it, then
// 1 + the end (exclusive) of the tile rows its members can touch, so that the strips below skip it.
#define SPLAT_BINDING_CLUSTER_ROWS 16
#define SPLAT_COMPACT_WORDS 5       // 32-bit words of one compact record
#define SPLAT_UNIFORM_FRAME 0       // FrameUniforms (uniform block binding)
#define SPLAT_IMAGE_COLOR 0         // the frame's display-space colour (rgba8), read and written
#define SPLAT_TEXTURE_VIEW_DEPTH 1  // the mesh pass's view depth (r32f), +inf where no mesh
// The same texture as an image: the step that writes the output pixels (the raster at render scale 1,
// else the upscale) reads its pixel's mesh depth there and leaves the nearer of it and the splats'
// depth (the depth at which their accumulated opacity first exceeds ½), for the passes after.
#define SPLAT_IMAGE_VIEW_DEPTH 7
// With SplatPassSettings::splat_depth (the SPLAT_DEPTH_IMAGE define): the splats' own depths at the
// output size (rg32f): x that median depth, y the expected depth Σ dᵢαᵢTᵢ / A; +inf where none.
#define SPLAT_IMAGE_SPLAT_DEPTH 6
#define SPLAT_INFINITY uintBitsToFloat(0x7f800000u)
// Buffer textures over the projected splats (rgba32f, 3 texels a splat) and the sorted values (r32ui),
// read by the raster with SplatPassSettings::raster_fetch = texel.
#define SPLAT_TEXTURE_PROJECTED 2
#define SPLAT_TEXTURE_VALUES 3
// Buffer textures over the project pass's inputs, read by it with raster_fetch = texel (as rgba32ui /
// rgb32ui, bit-exact: the Gaussians 4 texels each, the SH one texel per coefficient, the instances 9).
#define SPLAT_TEXTURE_GAUSSIANS 4
#define SPLAT_TEXTURE_SH 5
#define SPLAT_TEXTURE_INSTANCES 6
// ... and over the bin pass's input: the projected splats as rgba32ui (3 texels a splat, bit-exact, so
// that the bin walks the footprint step 1b counted).
#define SPLAT_TEXTURE_PROJECTED_WORDS 7
// ... and the sorted keys (rg32ui) for the tile-ranges pass.
#define SPLAT_TEXTURE_SORTED_KEYS 9
// With compact storage the project pass's views are the records and SH words (r32ui) and the page
// codecs (rgba32ui, 5 texels each).
#define SPLAT_TEXTURE_PAGE_CODECS 10
// Below render scale 1 (docs/algorithms.md §5) the raster writes these low-resolution images (rgba32f:
// premultiplied colour C and alpha A, and their ∂/∂x, ∂/∂y, ∂²/∂x∂y per low-res pixel; the front
// image, rgba32f: x the view depth where the transmittance first falls below ½, else the depth the
// texel was cut at, y that depth or +inf where it never fell below ½, z the expected depth
// Σ dᵢαᵢTᵢ / A or +inf where no splat was blended), which the upscale pass reads.
#define SPLAT_IMAGE_LOW_VALUE 1
#define SPLAT_IMAGE_LOW_DX 2
#define SPLAT_IMAGE_LOW_DY 3
#define SPLAT_IMAGE_LOW_DXY 4
#define SPLAT_IMAGE_LOW_FRONT 5
// The upscale pass's method (its UPSCALE_METHOD define), in the order of plugin_msgs::Upscaler.
#define SPLAT_UPSCALER_SPLINE 0
#define SPLAT_UPSCALER_BICUBIC 1
#define SPLAT_UPSCALER_BILINEAR 2
#define SPLAT_UPSCALER_LANCZOS3 3
#define SPLAT_UPSCALE_WORKGROUP_SIZE 8  // the upscale pass: 8×8 output pixels per workgroup

// The splat budget (SplatPassSettings::splat_budget): when the selection would draw more than N
// Gaussians, the frame selects as if every coverage were β times smaller, β = 2^(b/8) for the
// smallest bin b whose count fits (an eighth of an octave per bin: the LOD cut moves to coarser
// levels); if even the last bin does not fit, the smallest Gaussians of that cut are dropped by a
// coverage histogram of the same resolution. Both histograms are filled by step 1b and read by
// splat_budget.comp.glsl in the same frame, so no frame ever draws more than N.
#define SPLAT_BUDGET_BINS 96  // β from 1 to 2^(95/8) ≈ 3700
#define SPLAT_BUDGET_BINS_PER_OCTAVE 8.0
#define SPLAT_COVERAGE_BINS 256         // coverage 2^(k/8 − 8) px: 1/256 px … ≈ 2^24 px
#define SPLAT_COVERAGE_BIN_OFFSET 64.0  // 8 octaves below 1 px
// ProjectedSplat::conic.w holds, as float bits with bit 30 set (which keeps the value a normal float:
// no denormal flushing can change it), the splat's first key within its cluster in bits 0–29, for step 3.
// Under a budget step 1b stores the splat's bins there instead, which the trim (step 1d) replaces: first
// β bin (bits 0–7), last β bin (8–15), the Gaussian's index within its cluster (16–23), level − 1 (24–25).
#define SPLAT_BUDGET_PACK_FLAG 0x40000000u

// GpuInstance::info.z: the SH degree in the low byte; SPLAT_INSTANCE_HIDDEN set for a component that is
// resident but not drawn (SplatComponent::visible false): step 1a drops its clusters before any other
// test; SPLAT_INSTANCE_DISSOLVE set when the opacity factor (info.x) is the fraction of the Gaussians
// drawn rather than a factor on every opacity (SplatComponent::dissolve); the level handover (below).
#define SPLAT_INSTANCE_SH_DEGREE_MASK 0xFFu
#define SPLAT_INSTANCE_HIDDEN 0x100u
#define SPLAT_INSTANCE_DISSOLVE 0x200u
// Bits 10–11: how the cloud's levels hand over (plugin_msgs::LevelHandover: 0 unknown, 1 overlapping,
// 2 abutting); its Gaussians fade by FrameUniforms::transitions[that value].
#define SPLAT_INSTANCE_HANDOVER_SHIFT 10u
#define SPLAT_INSTANCE_HANDOVER_MASK 0xC00u

// Gaussians with their 3D covariance precomputed (local space of the cloud).
SPLAT_LOD_STRUCT(GpuGaussian) {
    vec4 position_opacity;  // xyz local mean, w activated opacity
    vec4 covariance_a;      // Σ xx, xy, xz, yy
    vec4 covariance_b;      // Σ yz, zz, w = uintBitsToFloat(instance index)
    vec4 lod;               // x coverage_min, y coverage_max, z level (1..4), w unused
};

// The ranges one page's compact records are quantised against (CompactPage in
// splat_lod/core/compact_gaussians.h, which states the record's bits).
SPLAT_LOD_STRUCT(GpuPageCodec) {
    vec4 position_lo;    // xyz, w: the log-scales' lo
    vec4 position_step;  // xyz, w: the log-scales' step
    vec4 colour_lo;      // rgb (the DC term as colour), w: lo of log2 of the coverage bounds
    vec4 colour_step;    // rgb, w: the coverage bounds' step
    vec4 sh_max;         // xyz: bands 1, 2, 3, the largest |coefficient|; w: the page's instance index as float bits
};

// One splat component this frame.
SPLAT_LOD_STRUCT(GpuInstance) {
    mat4 model;             // local → world
    mat4 rotation_inverse;  // world → local directions (for SH)
    uvec4 info;  // x floatBitsToUint(opacity factor, SplatComponent::opacity), y count, z SH degree used (bits 0-7),
                 // SPLAT_INSTANCE_HIDDEN and SPLAT_INSTANCE_DISSOLVE, w floatBitsToUint(‖M‖₂), M = mat3(model)
};

// What the project pass knows about the Gaussians one of its workgroups handles (cluster c holds
// Gaussians [c·SPLAT_PROJECT_WORKGROUP_SIZE, (c + 1)·SPLAT_PROJECT_WORKGROUP_SIZE)). Baked files
// are sorted by level and along a Morton curve, so a cluster is one level of one small region: when
// even its largest member would be too small to draw at the cluster's nearest depth, the whole
// workgroup skips its Gaussians (docs/algorithms.md §3 "not too small", bounded from above).
SPLAT_LOD_STRUCT(GpuCluster) {
    vec4 sphere;  // local-space centre xyz and radius w of the members' means; w < 0: an empty
                  // cluster (a freed or padding range of the scene), never projected
    vec4 bounds;  // x: max over members of sqrt(2·ln(255·o))·min(σ_max, √2·σ_mid) (local units; 0 if invisible)
                  // y: max over members of that extent / coverage_min (−1 when any member has no
                  //    coverage_min > 0: never skipped)
                  // z: highest member level; w: instance index as float bits, or −1 (mixed instances)
    vec4 reach;   // x: max over members of sqrt(2·ln(255·o))·σ_max, how far (local units) a member's
                  //    α = 1/255 ellipsoid reaches from its mean; −1: never frustum-culled
                  //    (non-finite bounds); yzw unused
};

// A projected Gaussian (SPLAT_BINDING_PROJECTED). Its tiles are not stored: every pass that needs them
// computes them from mean, conic and opacity (common_splat_tiles.glsl).
SPLAT_LOD_STRUCT(ProjectedSplat) {
    vec4 mean_depth;  // x, y image position (top-left origin), z view depth, w opacity
    vec4 conic;       // inverse of the dilated 2D covariance: xx, xy, yy; w its first key (below)
    vec4 color;       // rgb (SH + 0.5, clamped at 0); w the instance index with SPLAT_BUDGET_PACK_FLAG
                      // set (as float bits), under a budget the coverage S (output px) until step 1d
                      // has read it and put the instance there
};

// The frame's parameters (uniform block SPLAT_UNIFORM_FRAME, std140). Laid out so that std140 and
// the C++ struct agree without padding rules: each vec2/uvec2 at a multiple of 8 bytes, the vec3 followed
// by a float that fills its 16 bytes; gpu_layout.h checks the offsets.
SPLAT_LOD_STRUCT(FrameUniforms) {
    mat4 view;                   // world → view
    vec3 camera_position;        // world
    float znear;                 // the near plane of the selection and raster (docs/algorithms.md §1)
    vec2 focal;                  // fx, fy (raster pixels)
    vec2 principal;              // cx, cy (raster pixels)
    vec2 raster_size;            // raster width, height (px)
    vec2 jacobian_clamp;         // 1.3·tan(fov_x/2), 1.3·tan(fov_y/2) of the output camera
    float dilation;              // the EWA low-pass (raster px²)
    uint mip_filter;             // 1: Mip-Splatting's 2D filter
    uint cluster_skipping;       // 1: step 1a skips clusters that are all too small
    uint frustum_culling;        // 1: step 1a culls clusters outside the view
    uint gaussian_count;         // Gaussians in the scene's buffers (pages included)
    uint sh_stride;              // SH per Gaussian: floats (full storage) or words (compact)
    uint key_capacity;           // (depth, tile) keys the key buffer holds
    uint instance_count;         // GpuInstance records
    uvec2 tiles;                 // tiles_x, tiles_y
    uint tile_count;             // tiles_x · tiles_y
    uint tile_size;              // tile side (px)
    float size_threshold;        // S_T (px)
    float rel_min;               // S_rel_min
    float rel_max;               // S_rel_max
    float coverage_scale;        // output px per raster px (1/s): coverage is measured at the output
    uint lod_flags;              // SPLAT_LOD_ALL_LEVELS | SPLAT_LOD_COVERAGE_RULE | SPLAT_LOD_TRANSITIONS
    uint finest_level;           // finest bake level drawn
    uint coarsest_level;         // highest bake level present
    uint level_colouring;        // 1: debug view, tint each Gaussian by its level
    vec2 output_size;            // output width, height (px)
    float render_scale;          // s (1 natively)
    float inverse_render_scale;  // 1/s
    uint splat_budget;           // at most this many Gaussians drawn (0: no budget)
    uint strip_first_row;        // the tile rows this run of steps 1–6 draws: [first, end) (all of them
                                 // unless the frame is drawn in strips, SplatPassSettings::frame_memory_limit)
    uint exact_tiles;            // 1: a splat's keys are the tiles its ellipse touches, 0: its bounding box
    uint key_depth_bits;         // D > 0: one-word sort keys (tile << D | depth_q), 0: (depth bits, tile)
    uint splat_capacity;         // ProjectedSplat entries SPLAT_BINDING_PROJECTED holds
    uint sh_storage_degree;      // SH degree the scene stores (compact: how its SH words are laid out)
    uint separate_selection;     // 1: coverage and skipping by selection_view (a stereo eye), 0: by view
    uint strip_end_row;
    mat4 selection_view;  // world → view of the camera that selects (CameraView::selection_view)
    // How Gaussians fade at the rule's switches, one per level handover (the instance's
    // SPLAT_INSTANCE_HANDOVER bits; the rule resolved per asset, plugin_msgs::LodRule::for_asset): x the
    // band in octaves of coverage (0: hard switching, and always 0 in modes without transitions), y and
    // z how far the "too small" fade-out and the "too large" fade-in lie past their switch
    // (plugin_msgs::transition_shifts), w unused.
    vec4 transitions[3];
};

// Written by the GPU each frame; the CPU reads `projected` and the pair total after step 2, and the
// rest asynchronously.
SPLAT_LOD_STRUCT(FrameCounters) {
    uint projected;  // splats step 1b projected (reserved in SPLAT_BINDING_PROJECTED; may exceed its capacity)
    uint visible;
    uint keys_needed;   // tile-splat pairs this frame asked for
    uint overflowed;    // 1 when keys_needed > key capacity (the frame dropped pairs)
    uvec4 per_level;    // visible Gaussians per LOD level 1..4
    uvec4 skipping;     // x: Gaussians in project workgroups skipped as too small (GpuCluster),
                        // y: Gaussians in clusters culled by the view frustum, z: in clusters of hidden
                        // instances (SPLAT_INSTANCE_HIDDEN); w unused
    uvec4 budget;       // x: β bin chosen (0: the budget did not bind), y: coverage bin below which the
                        // last cut's Gaussians were dropped (0: none), z: Gaussians the selection
                        // would have drawn without the budget, w unused
    uvec4 depth_range;  // x: the float bits of the largest view depth projected, y: ~(those of the
                        // smallest), both by atomicMax from 0; z, w unused
};

// Picking (SplatRenderer::pick): the pixels asked this frame and, per pixel, what splat_pick.comp.glsl
// found along its ray.
#define SPLAT_MAX_PICKS 64
SPLAT_LOD_STRUCT(SplatPicks) {
    uvec4 count;                     // x: pixels asked (at most SPLAT_MAX_PICKS); yzw unused
    uvec4 pixels[SPLAT_MAX_PICKS];   // xy: the raster pixel, zw: the output pixel
    uvec4 answers[SPLAT_MAX_PICKS];  // x: float bits of the view depth where the accumulated opacity first
                                     // passes ½ (+inf: never, before the mesh); y: the instance index of
                                     // the splat that makes it pass; zw unused
};

// The splat budget's per-frame state (SPLAT_BINDING_BUDGET), cleared by the CPU each frame.
SPLAT_LOD_STRUCT(SplatBudgetState) {
    uvec4 choice;                        // x: β bin, y: coverage cut bin, z: count at β = 1, w unused
    uint selected[SPLAT_BUDGET_BINS];    // difference array: +1 at a Gaussian's first bin, −1 after its last
    uint coverage[SPLAT_COVERAGE_BINS];  // Gaussians still selected at the last β bin, by coverage bin
};

#ifdef __cplusplus
}  // namespace splat_lod::gpu
#endif

#endif  // SPLAT_LOD_SHARED_H
