// Step 1b, cull + project + colour (docs/algorithms.md §1): one workgroup per cluster step 1a kept, one
// invocation per Gaussian. The cluster's survivors go to one run of the dense splat array, reserved
// with a single atomic, in their Gaussians' order, each with its first key within the cluster; the
// cluster records that run and the number of raster tiles (frame.tile_size px a side) its splats'
// footprints touch (common_splat_tiles.glsl). A scan over the clusters then gives every cluster its
// range of keys. The frame's depth range (FrameCounters::depth_range) sizes the sort keys' depth bits
// in step 3.
#include "common_splat_bindings.glsl"

layout(local_size_x = SPLAT_PROJECT_WORKGROUP_SIZE) in;
layout(std430, binding = SPLAT_BINDING_INSTANCES) readonly buffer Instances { GpuInstance instances[]; };
layout(std430, binding = SPLAT_BINDING_PROJECTED) writeonly buffer Projected { ProjectedSplat projected[]; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_PAIRS) writeonly buffer ClusterPairs { uint cluster_pairs[]; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_SPLATS) writeonly buffer ClusterSplats { uvec2 cluster_splats[]; };
layout(std430, binding = SPLAT_BINDING_STATS) buffer Stats { FrameCounters stats; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_LIST) readonly buffer ClusterList { uvec4 dispatch; uint ids[]; } cluster_list;
layout(std430, binding = SPLAT_BINDING_BUDGET) buffer Budget { SplatBudgetState budget; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_ROWS) buffer ClusterRows { uint cluster_rows[]; };

#ifdef SPLAT_INPUT_TEXELS
// On CPU drivers a storage-buffer load is a loop over the SIMD lanes and a texel fetch one gather
// (docs/algorithms.md §1): the instances read through a buffer texture, as unsigned words (bit-exact),
// like the Gaussians (common_splat_storage.glsl).
layout(binding = SPLAT_TEXTURE_INSTANCES) uniform usamplerBuffer instance_texels;  // rgba32ui, 9 per instance
GpuInstance load_instance(uint index) {
    int b = int(index) * 9;
    vec4 c[8];
    for (int k = 0; k < 8; ++k) c[k] = uintBitsToFloat(texelFetch(instance_texels, b + k));
    return GpuInstance(mat4(c[0], c[1], c[2], c[3]), mat4(c[4], c[5], c[6], c[7]), texelFetch(instance_texels, b + 8));
}
#else
GpuInstance load_instance(uint index) { return instances[index]; }
#endif
#include "common_splat_storage.glsl"
#include "common_splat_sh.glsl"
#include "common_splat_lod.glsl"
#include "common_splat_tiles.glsl"
#include "common_splat_cluster_scan.glsl"

// The view transform into a camera frame whose y points down the image and z forward (so that
// the 3DGS Jacobian applies as written); F = diag(1, −1, −1).
const mat3 VIEW_TO_CAMERA = mat3(1, 0, 0, 0, -1, 0, 0, 0, -1);

mat3 local_covariance(GpuGaussian g) {
    vec4 a = g.covariance_a, b = g.covariance_b;
    return mat3(a.x, a.y, a.z, a.y, a.w, b.x, a.z, b.x, b.y);
}

// The undilated 2D covariance of a Gaussian of local covariance `local` seen through `view` (world →
// view), its mean at camera-space `cam`: Σ2D = J T Σ Tᵀ Jᵀ, T = F·W·M; x/z and y/z clamped to
// 1.3·tan(fov/2) as 3DGS does.
mat2 screen_covariance(mat4 view, mat3 model, mat3 local, vec3 cam) {
    mat3 t = VIEW_TO_CAMERA * mat3(view) * model;
    mat3 sigma = t * local * transpose(t);
    float fx = frame.focal.x, fy = frame.focal.y, z = cam.z;
    float tx = clamp(cam.x / z, -frame.jacobian_clamp.x, frame.jacobian_clamp.x) * z;
    float ty = clamp(cam.y / z, -frame.jacobian_clamp.y, frame.jacobian_clamp.y) * z;
    mat3x2 j = mat3x2(fx / z, 0.0, 0.0, fy / z, -fx * tx / (z * z), -fy * ty / (z * z));
    return mat2(j * sigma * transpose(j));
}

// The coverage that selects the Gaussian (docs/algorithms.md §2), at the output resolution (what the
// viewer sees), also when the splats are rasterised smaller for upscaling (§5). A stereo eye takes its
// centre's (frame.selection_view, engine::stereo_eyes), so that both eyes draw the same selection;
// where the Gaussian is not in front of the centre, its own.
float selection_coverage(mat2 cov, float det, float opacity, vec3 world, mat3 model, mat3 local) {
    if (frame.separate_selection != 0u) {
        vec3 cam = VIEW_TO_CAMERA * (frame.selection_view * vec4(world, 1.0)).xyz;
        if (cam.z > frame.znear) {
            cov = screen_covariance(frame.selection_view, model, local, cam);
            det = cov[0][0] * cov[1][1] - cov[0][1] * cov[0][1];
        }
    }
    return pixel_coverage(cov, det, opacity) * frame.coverage_scale;
}

// SplatComponent::dissolve: a pseudo-random rank in [0, 1) of a scene slot (an integer hash, xor-shift-
// multiply rounds), so that about the fraction f of any component's Gaussians, a fixed subset while it
// stays resident, rank below f.
float dissolve_rank(uint slot) {
    uint h = slot * 0x9E3779B9u;
    h ^= h >> 16;
    h *= 0x21F0AAADu;
    h ^= h >> 15;
    h *= 0x735A2D97u;
    h ^= h >> 15;
    return float(h >> 8) * (1.0 / 16777216.0);
}

// In strips: notes that the Gaussian at `index` may touch tile rows up to `end` (exclusive) over the
// whole raster (SPLAT_BINDING_CLUSTER_ROWS), so that step 1a leaves its cluster out of the strips below.
void note_rows(uint index, uint end) {
    atomicMax(cluster_rows[index / uint(SPLAT_PROJECT_WORKGROUP_SIZE)], 1u + min(end, frame.tiles.y));
}

// In strips (SplatPassSettings::frame_memory_limit): true when Gaussian `g` at camera-space `cam` cannot
// reach the strip's pixel rows, so that the Gaussians of a cluster that straddles a strip's edge skip the
// rest of their projection when they lie beyond it. Its α = 1/255 ellipsoid reaches at most
// sqrt(2·ln(255·o)·trace Σ) ≥ sqrt(2·ln(255·o))·σ_max from its mean, which bounds its footprint's
// half-height as step 1a's cull_cluster bounds a cluster's (splat_clusters.comp.glsl). Exact: such a
// Gaussian has no tile in the strip. One below the strip notes the rows it may reach.
bool outside_strip(uint index, GpuGaussian g, vec3 cam, GpuInstance inst) {
    float trace = g.covariance_a.x + g.covariance_a.w + g.covariance_b.y;
    float reach = sqrt(max(2.0 * log(255.0 * g.position_opacity.w) * trace, 0.0));
    float fx = frame.focal.x, fy = frame.focal.y, lx = frame.jacobian_clamp.x, ly = frame.jacobian_clamp.y;
    float j = sqrt(fx * fx * (1.0 + lx * lx) + fy * fy * (1.0 + ly * ly));
    float margin = 1.0 + sqrt(2.0 * log(255.0) * frame.dilation) * 1.001;
    float radius = (reach * uintBitsToFloat(inst.info.w) * j * 1.001 + 1e-3) / cam.z + margin;
    float y = frame.principal.y + fy * cam.y / cam.z;
    float top = float(frame.strip_first_row * frame.tile_size);
    float bottom = min(float(frame.strip_end_row * frame.tile_size), frame.raster_size.y);
    if (y - radius > bottom) note_rows(index, uint(clamp(floor((y + radius) / float(frame.tile_size)), 0.0, 65535.0)) + 1u);
    return y + radius < top || y - radius > bottom;
}

// Returns the tile count; 0 means culled. The projected form goes to `p`.
uint project(uint index, out ProjectedSplat p) {
    GpuGaussian g = load_gaussian(index);
    GpuInstance inst = load_instance(floatBitsToUint(g.covariance_b.w));
    vec3 world = (inst.model * vec4(g.position_opacity.xyz, 1.0)).xyz;
    vec3 cam = VIEW_TO_CAMERA * (frame.view * vec4(world, 1.0)).xyz;
    float z = cam.z;
    float opacity = g.position_opacity.w;
    if (!(z > frame.znear) || !(opacity > 1.0 / 255.0)) return 0u;
    if (drawn_in_strips() && outside_strip(index, g, cam, inst)) return 0u;

    mat3 local = local_covariance(g);
    mat2 cov = screen_covariance(frame.view, mat3(inst.model), local, cam);
    float det_undilated = cov[0][0] * cov[1][1] - cov[0][1] * cov[0][1];
    float coverage = selection_coverage(cov, det_undilated, opacity, world, mat3(inst.model), local);
    // Under a splat budget every Gaussian selected at some β is projected; the budget pass then
    // picks β and the trim pass keeps those selected at it and applies their weight at β. Otherwise
    // the opacity is scaled by the LOD weight here (smooth transitions; 1 with hard switching). Both
    // scale after the mip filter, so that a budget that does not bind draws the same bytes.
    bool budgeted = frame.splat_budget != 0u;
    uint level = clamp(uint(g.lod.z), 1u, 4u);
    vec3 transition = instance_transition(inst.info.z);
    ivec2 bins = budgeted ? budget_bins(uint(g.lod.z), coverage, g.lod.x, g.lod.y, transition) : ivec2(0);
    float weight = budgeted ? 1.0 : lod_weight(uint(g.lod.z), coverage, g.lod.x, g.lod.y, transition);
    if (bins.y < bins.x || !(weight > 0.0)) return 0u;
    float dilation = frame.dilation;
    cov[0][0] += dilation;
    cov[1][1] += dilation;
    float det = cov[0][0] * cov[1][1] - cov[0][1] * cov[0][1];
    if (!(det > 0.0)) return 0u;
    if (frame.mip_filter != 0u) opacity *= sqrt(max(det_undilated, 0.0) / det);  // optional 2D mip filter
    // The component's opacity factor: a streamed part fading in or out draws that fraction of its
    // Gaussians (dissolve), any other component scales every opacity by it.
    float factor = uintBitsToFloat(inst.info.x);
    if ((inst.info.z & SPLAT_INSTANCE_DISSOLVE) != 0u) {
        if (!(dissolve_rank(index) < factor)) return 0u;
    } else {
        opacity *= factor;
    }
    opacity *= weight;
    if (!(opacity > 1.0 / 255.0)) return 0u;

    vec2 mean = vec2(frame.principal.x + frame.focal.x * cam.x / z, frame.principal.y + frame.focal.y * cam.y / z);
    vec4 conic = vec4(vec3(cov[1][1], -cov[0][1], cov[0][0]) / det, 0.0);
    // The tiles it touches; a splat whose footprint holds no pixel centre of the raster (or is not a
    // number) draws nothing and is culled here. In strips, first the rows it touches over the whole raster.
    bool strips = drawn_in_strips();
    TileFootprint whole = TileFootprint(mean, 0.0, 0.0, 0.0, 0.0, ivec2(1), ivec2(0), uvec4(0u));  // unused
    if (strips) {
        whole = whole_footprint(mean, conic, opacity);
        note_rows(index, whole.rect.w);
    }
    uint tiles = splat_tile_count(mean, conic, opacity);
    if (tiles == 0u) return 0u;
    // Bin 0 (β = 1) counts exactly what the frame without a budget draws: not a splat whose opacity
    // weighted at β = 1 is below 1/255 or whose footprint with it holds no pixel centre; the trim pass
    // drops those at any β. The tiles counted here are the unweighted footprint's, which holds every
    // weight's; the trim recounts them at its β.
    if (budgeted && bins.x == 0) {
        float weighted = opacity * lod_weight(uint(g.lod.z), coverage, g.lod.x, g.lod.y, transition);
        if (splat_tile_count(mean, conic, weighted) == 0u) {
            bins.x = 1;
            if (bins.y < 1) return 0u;
        }
    }

    vec3 direction = normalize(mat3(inst.rotation_inverse) * (world - frame.camera_position));
    vec3 color = evaluate_sh(index, inst.info.z & SPLAT_INSTANCE_SH_DEGREE_MASK, direction);
    if (frame.level_colouring != 0u) color = level_colour(level, color);  // debug view

    if (budgeted) {
        uint cbin = coverage_bin(coverage);
        uint local = index % SPLAT_PROJECT_WORKGROUP_SIZE;
        conic.w = uintBitsToFloat(SPLAT_BUDGET_PACK_FLAG | uint(bins.x) | (uint(bins.y) << 8) | (local << 16) |
                                  ((level - 1u) << 24));
        atomicAdd(budget.selected[bins.x], 1u);
        if (bins.y + 1 < SPLAT_BUDGET_BINS) atomicAdd(budget.selected[bins.y + 1], 0xFFFFFFFFu);  // −1
        else atomicAdd(budget.coverage[cbin], 1u);
    } else if (!strips || first_tile_row(whole) >= frame.strip_first_row) {
        atomicAdd(stats.visible, 1u);  // in strips, by the strip of its first tile row (the frame's count)
        atomicAdd(stats.per_level[level - 1u], 1u);
    }
    atomicMax(stats.depth_range.x, floatBitsToUint(z));  // positive floats order like their bits
    atomicMax(stats.depth_range.y, ~floatBitsToUint(z));
    // color.w: under a budget the coverage, from which the trim computes the weight at its β (and puts
    // the instance there); otherwise the instance, for picking.
    float instance = uintBitsToFloat(SPLAT_BUDGET_PACK_FLAG | floatBitsToUint(g.covariance_b.w));
    p = ProjectedSplat(vec4(mean, z, opacity), conic, vec4(color, budgeted ? coverage : instance));
    return tiles;
}

shared uint s_first;  // the cluster's first entry in the dense array

void main() {
    uint lid = gl_LocalInvocationIndex;
    uint cluster = cluster_list.ids[gl_WorkGroupID.x];
    uint index = cluster * SPLAT_PROJECT_WORKGROUP_SIZE + lid;
    ProjectedSplat p;
    uint tiles = index < frame.gaussian_count ? project(index, p) : 0u;
    // Each visible splat's place among the cluster's and its first key within the cluster.
    scan_cluster(lid, uvec2(tiles > 0u ? 1u : 0u, tiles));
    // One reservation for the cluster; a cluster that does not fit writes nothing (the CPU sees the
    // count above the capacity and runs the frame's steps 1–2 again with a larger array). In strips the
    // cluster is marked as projected: none of its members reaches the rows below those they noted.
    if (lid == 0u) {
        if (drawn_in_strips()) atomicMax(cluster_rows[cluster], 1u);
        uint count = s_scan_total.x;
        uint first = count > 0u ? atomicAdd(stats.projected, count) : 0u;
        bool fits = first + count <= frame.splat_capacity && first + count >= first;
        cluster_splats[cluster] = uvec2(first, fits ? count : 0u);
        cluster_pairs[cluster] = fits ? s_scan_total.y : 0u;
        s_first = fits ? first : 0xFFFFFFFFu;
    }
    barrier();
    if (tiles == 0u || s_first == 0xFFFFFFFFu) return;
    uvec2 before = cluster_prefix(lid);
    if (frame.splat_budget == 0u) p.conic.w = uintBitsToFloat(SPLAT_BUDGET_PACK_FLAG | before.y);
    projected[s_first + before.x] = p;
}
