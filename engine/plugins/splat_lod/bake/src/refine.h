#pragma once
// Internal to the bake (docs/algorithms.md §4): step 7, the refinement of each coarse level against the fine model.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include <optional>

#include "coverage.h"
#include "stage_clock.h"

namespace splat_lod::bake::detail {

// Step 7 (refine.cpp): the distillation of each coarse level against the fine model. Holds the
// fine model's full-resolution renders (clamped to [0, 1]) of the refinement cameras, made once
// and area-averaged per level.
class Refiner {
public:
    // `fine` is the level-1 scene; `cameras` all bake cameras (the refinement picks its subset).
    Refiner(const SplatCloud& fine, const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options);
    bool usable() const { return !cameras_.empty(); }

    // Adam on the SH DC and opacity logit of `level`'s Gaussians of `cloud` (every level present,
    // ranges set), one camera per iteration; the selection (docs/algorithms.md §3, mode full) at the
    // level's scale is computed once per camera and held fixed.
    void refine_level(SplatCloud& cloud, int level, LevelSummary& summary) const;
    // Mean PSNR (dB) over the refinement cameras of the `full` selection of `cloud` at the level's
    // scale against the targets.
    double evaluate(const SplatCloud& cloud, int level) const;

private:
    BakeOptions options_;
    std::vector<reference::ReferenceCamera> cameras_;  // the refinement's subset
    std::vector<std::vector<double>> targets_;         // full-resolution RGB in [0, 1] per camera
};

// The cameras the refinement uses: image sides divisible by 64 and the focal length of the first
// such camera; at most `limit`, spread evenly over the set. Empty when none qualifies.
std::vector<std::size_t> refinement_cameras(const std::vector<reference::ReferenceCamera>& cameras, int limit);

// The camera at render scale k: focal lengths, principal point and size divided by k.
reference::ReferenceCamera scaled_camera(const reference::ReferenceCamera& camera, int k);

// Step 7 for every coarse level that gained Gaussians, finest first (each is refined with the finer
// ones already settled); `shared_refiner` when the caller has one, else one made in `own_refiner`.
// Returns the refiner that ran (its targets serve the final check), or null.
const Refiner* refine_levels(SplatCloud& cloud, const SplatCloud& fine,
                             const std::vector<reference::ReferenceCamera>& cameras, const BakeOptions& options,
                             const Refiner* shared_refiner, std::optional<Refiner>& own_refiner, BakeSummary& summary,
                             StageClock& clock);

}  // namespace splat_lod::bake::detail
