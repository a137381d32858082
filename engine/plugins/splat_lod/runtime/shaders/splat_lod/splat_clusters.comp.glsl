// Step 1a, cluster culling and skipping: one invocation per project workgroup's cluster
// (GpuCluster). Clusters that the view frustum leaves out and clusters whose Gaussians are all too
// small for this view are counted and left out; the others are
// appended to the list that step 1b dispatches over (indirectly), so skipped Gaussians cost nothing
// beyond their share of this pass. The list's order depends on scheduling, the result does not
// (splat_project.comp.glsl).
#include "common_splat_bindings.glsl"

layout(local_size_x = SPLAT_CLUSTER_WORKGROUP_SIZE) in;
layout(std430, binding = SPLAT_BINDING_INSTANCES) readonly buffer Instances { GpuInstance instances[]; };
layout(std430, binding = SPLAT_BINDING_STATS) buffer Stats { FrameCounters stats; };
layout(std430, binding = SPLAT_BINDING_CLUSTERS) readonly buffer Clusters { GpuCluster clusters[]; };
layout(std430, binding = SPLAT_BINDING_CLUSTER_LIST) buffer ClusterList { uvec4 dispatch; uint ids[]; } cluster_list;
layout(std430, binding = SPLAT_BINDING_CLUSTER_ROWS) readonly buffer ClusterRows { uint cluster_rows[]; };

#include "common_splat_lod.glsl"

const mat3 VIEW_TO_CAMERA = mat3(1, 0, 0, 0, -1, 0, 0, 0, -1);

// True when no Gaussian of the cluster can pass "not too small" (docs/algorithms.md §3) this frame. For a
// member with extent e = sqrt(2·ln(255·o))·min(σ_max, √2·σ_mid), coverage S ≤ 2·e·‖M‖₂·‖J‖₂ (the
// shorter chord of the α = 1/255 ellipse; see build_clusters in gpu_scene.cpp), and ‖J‖₂ ≤ ‖J‖_F ≤ sqrt(fx²(1 + lx²) + fy²(1 + ly²)) / z
// with lx, ly the Jacobian's clamp of x/z, y/z; z is at least the sphere's nearest depth. If for
// every member that bound is below S_T and its ratio to S_min below S_rel_min, none is drawn.
// Members of the coarsest level, members without S_min, and clusters reaching the near plane are
// never skipped. Smooth transitions change nothing here: a member fades out before its switch, never
// past it.
// True when no member of the cluster can touch the image (exact: step 1b would cull every one).
// A member at camera-space (x, y, z), z > 0, has its mean at u = cx + fx·x/z and reaches at most
// r = √L·‖J‖₂·‖M‖₂·σ_max + √(L·dilation) pixels from it, with ‖J‖₂ ≤ j/z (the Jacobian's clamp, as in
// skip_cluster) and √L·σ_max ≤ reach. So it misses the image's right side when
// fx·x − a·z > reach·‖M‖₂·j with a = W + 1 + √(L_max·dilation) − cx (one pixel of margin), a
// half-space test; the smallest value over the sphere of means is the centre's minus the radius
// times the plane normal's length. Likewise left, top and bottom; and when the whole sphere lies
// at z ≤ znear, step 1b culls every member at the near plane. The top and bottom sides are those of
// the pixel rows [top, bottom): the raster's, or a strip's (SplatPassSettings::frame_memory_limit).
bool cull_cluster(GpuCluster c, float top, float bottom) {
    if (frame.frustum_culling == 0u || !(c.reach.x >= 0.0) || c.bounds.w < 0.0) return false;
    GpuInstance inst = instances[floatBitsToUint(c.bounds.w)];
    float stretch = uintBitsToFloat(inst.info.w);
    vec3 p = VIEW_TO_CAMERA * (frame.view * (inst.model * vec4(c.sphere.xyz, 1.0))).xyz;
    float radius = c.sphere.w * stretch * 1.0001;
    if (p.z + radius < frame.znear) return true;
    float fx = frame.focal.x, fy = frame.focal.y, lx = frame.jacobian_clamp.x, ly = frame.jacobian_clamp.y;
    float j = sqrt(fx * fx * (1.0 + lx * lx) + fy * fy * (1.0 + ly * ly));
    float reach = c.reach.x * stretch * j * 1.001 + 1e-3;
    float margin = 1.0 + sqrt(2.0 * log(255.0) * frame.dilation) * 1.001;
    // Planes n·p > reach with n = (±f, 0, −a) or (0, ±f, −a): a member is outside when n·p > reach.
    vec4 sides[4] = vec4[](vec4(fx, 0.0, -(frame.raster_size.x + margin - frame.principal.x), 0.0),
                           vec4(-fx, 0.0, -(frame.principal.x + margin), 0.0),
                           vec4(0.0, fy, -(bottom + margin - frame.principal.y), 0.0),
                           vec4(0.0, -fy, -(frame.principal.y - top + margin), 0.0));
    for (int k = 0; k < 4; ++k) {
        vec3 n = sides[k].xyz;
        if (dot(n, p) - radius * length(n) > reach) return true;
    }
    return false;
}

bool skip_cluster(uint cluster) {
    if (frame.cluster_skipping == 0u || (frame.lod_flags & SPLAT_LOD_COVERAGE_RULE) == 0u) return false;
    GpuCluster c = clusters[cluster];
    if (!(c.bounds.y > 0.0) || c.bounds.w < 0.0 || uint(c.bounds.z) >= frame.coarsest_level) return false;
    GpuInstance inst = instances[floatBitsToUint(c.bounds.w)];
    float stretch = uintBitsToFloat(inst.info.w);
    // By the camera that selects (a stereo eye's centre), as step 1b's coverage.
    vec3 centre = VIEW_TO_CAMERA * (frame.selection_view * (inst.model * vec4(c.sphere.xyz, 1.0))).xyz;
    float z_min = centre.z - c.sphere.w * stretch;
    if (!(z_min > frame.znear)) return false;
    float fx = frame.focal.x, fy = frame.focal.y, lx = frame.jacobian_clamp.x, ly = frame.jacobian_clamp.y;
    float jacobian = sqrt(fx * fx * (1.0 + lx * lx) + fy * fy * (1.0 + ly * ly)) / z_min;
    // × the coverage scale: selection uses the coverage at the output resolution (splat_project).
    float scale = 2.0 * stretch * jacobian * frame.coverage_scale * 1.001;  // margin for float rounding
    // With smooth transitions a Gaussian's weight is 0 from its instance's "too small" shift past that
    // switch on (lod_weight): the thresholds move down by that much (by nothing when its fade lies
    // before the switch, placements inside and before, or the mode has no transitions).
    vec3 transition = instance_transition(inst.info.z);
    float shift = exp2(smooth_transitions(transition) ? -transition.y : 0.0);
    return c.bounds.x * scale < frame.size_threshold * shift && c.bounds.y * scale < frame.rel_min * shift;
}

void main() {
    uint cluster = gl_GlobalInvocationID.x;
    uint count = frame.gaussian_count;
    uint first = cluster * SPLAT_PROJECT_WORKGROUP_SIZE;
    if (first >= count) return;
    if (clusters[cluster].sphere.w < 0.0) return;  // an empty range of the scene (GpuScene): no members
    // A resident component that is not drawn now (a streamed part the cut does not use).
    float instance = clusters[cluster].bounds.w;
    if (instance >= 0.0 && (instances[floatBitsToUint(instance)].info.z & SPLAT_INSTANCE_HIDDEN) != 0u) {
        if (frame.strip_first_row == 0u)
            atomicAdd(stats.skipping.z, min(uint(SPLAT_PROJECT_WORKGROUP_SIZE), count - first));
        return;
    }
    // The frame's statistics count each cluster once: in strips, by the whole raster in the first strip.
    bool counted = frame.strip_first_row == 0u;
    if (cull_cluster(clusters[cluster], 0.0, frame.raster_size.y)) {
        if (counted) atomicAdd(stats.skipping.y, min(uint(SPLAT_PROJECT_WORKGROUP_SIZE), count - first));
        return;
    }
    if (skip_cluster(cluster)) {
        if (counted) atomicAdd(stats.skipping.x, min(uint(SPLAT_PROJECT_WORKGROUP_SIZE), count - first));
        return;
    }
    float top = float(frame.strip_first_row * frame.tile_size);
    float bottom = min(float(frame.strip_end_row * frame.tile_size), frame.raster_size.y);
    if (drawn_in_strips()) {
        if (cull_cluster(clusters[cluster], top, bottom)) return;  // outside this strip
        // A strip above projected it, and none of its members reaches this strip's rows (splat_project).
        uint rows = cluster_rows[cluster];
        if (rows > 0u && rows - 1u <= frame.strip_first_row) return;
    }
    cluster_list.ids[atomicAdd(cluster_list.dispatch.x, 1u)] = cluster;
}
