// Step 1c, the splat budget's choice (splat_lod_shared.h, SplatBudgetState): one invocation reads
// the histograms step 1b filled this frame and picks the smallest β bin whose selection fits in
// the budget N; when even the last bin does not fit, the coverage cut that keeps at most N of that
// bin's Gaussians, the largest first. No read-back: step 1d reads the choice on the GPU.
#include "common_splat_bindings.glsl"

layout(local_size_x = 1) in;
layout(std430, binding = SPLAT_BINDING_STATS) buffer Stats { FrameCounters stats; };
layout(std430, binding = SPLAT_BINDING_BUDGET) buffer Budget { SplatBudgetState budget; };

void main() {
    uint n = frame.splat_budget;
    uint running = 0u, unbudgeted = 0u;
    uint chosen = uint(SPLAT_BUDGET_BINS);
    for (uint b = 0u; b < uint(SPLAT_BUDGET_BINS); ++b) {
        running += budget.selected[b];  // modular: the −1 entries are 0xFFFFFFFF
        if (b == 0u) unbudgeted = running;
        if (running <= n) {
            chosen = b;
            break;
        }
    }
    uint cut = 0u;
    // Without the rule (baseline, insert_large) β changes nothing: only the size cut applies.
    bool rule = (frame.lod_flags & SPLAT_LOD_COVERAGE_RULE) != 0u;
    if (!rule && chosen != 0u) chosen = uint(SPLAT_BUDGET_BINS);
    if (chosen == uint(SPLAT_BUDGET_BINS)) {  // the coarsest cut is still too many: drop its smallest
        chosen = rule ? uint(SPLAT_BUDGET_BINS) - 1u : 0u;
        uint kept = 0u;
        cut = uint(SPLAT_COVERAGE_BINS);
        for (int k = SPLAT_COVERAGE_BINS - 1; k >= 0; --k) {
            if (kept + budget.coverage[k] > n) break;
            kept += budget.coverage[k];
            cut = uint(k);
        }
    }
    budget.choice = uvec4(chosen, cut, unbudgeted, 0u);
    stats.budget = uvec4(chosen, cut, unbudgeted, 0u);
}
