// An exclusive prefix over a cluster's invocations (one project workgroup, SPLAT_PROJECT_WORKGROUP_SIZE
// of them), in invocation order: steps 1b and 1d number a cluster's splats with it and give each its
// first key within the cluster, so that step 3 needs neither a scan nor a barrier of its own. Done in
// runs of 8 and then over the runs, in two barriers: on CPU drivers every barrier switches between all
// the invocations of the workgroup.

shared uvec2 s_scan[SPLAT_PROJECT_WORKGROUP_SIZE];       // within its run of 8
shared uvec2 s_scan_runs[SPLAT_PROJECT_WORKGROUP_SIZE / 8];  // of each run
shared uvec2 s_scan_total;

// Every invocation of the workgroup calls it with its value, in uniform control flow. Afterwards
// invocation 0 may read s_scan_total; the prefixes (cluster_prefix) are visible to all only after the
// caller's next barrier.
void scan_cluster(uint lid, uvec2 value) {
    s_scan[lid] = value;
    barrier();
    if (lid < SPLAT_PROJECT_WORKGROUP_SIZE / 8) {
        uvec2 sum = uvec2(0u);
        for (uint k = lid * 8u; k < lid * 8u + 8u; ++k) {
            uvec2 v = s_scan[k];
            s_scan[k] = sum;
            sum += v;
        }
        s_scan_runs[lid] = sum;
    }
    barrier();
    if (lid == 0u) {
        uvec2 sum = uvec2(0u);
        for (uint k = 0u; k < SPLAT_PROJECT_WORKGROUP_SIZE / 8; ++k) {
            uvec2 v = s_scan_runs[k];
            s_scan_runs[k] = sum;
            sum += v;
        }
        s_scan_total = sum;
    }
}

// The sum of the values of the invocations before `lid`.
uvec2 cluster_prefix(uint lid) {
    return s_scan_runs[lid / 8u] + s_scan[lid];
}
