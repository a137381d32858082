#pragma once
// The splat budget's controller: at most LodSettings::splat_budget Gaussians drawn per frame, obeyed by
// both the splat pass and a streamed world's cut. Whoever sets the budget owns one (the game beside its
// streamer, the drop-in LOD's streamed world beside its own).
//   - The pass obeys within the frame: it reads the budget from LodSettings and picks, on the GPU, the
//     scale β of its size threshold that fits (docs/lod.md, "Splat budget").
//   - A chunk group's Gaussians are drawn whole, so β cannot thin a far view made of groups: the cut must
//     choose coarser groups instead. The controller reads the pass's plugin_msgs::SplatStatistics (a few
//     frames late) and gives the cut's scale of group_cell_px for the next update (cut_scale(),
//     StreamView::cut_scale): × √(unbudgeted / budget) while the budget is exceeded (at most 2^(1/4) a
//     step), held between 70 % and 100 % of it, eased back by 2^(1/8) a step below (stream_policy.h,
//     next_group_cell_scale()). Without a budget it is 1.
#include <optional>

#include "splat_lod/msgs/splat_statistics.h"

#include "engine/core/message_bus.h"

namespace splat_lod::world {

class SplatBudgetController {
public:
    // Listens to the pass's statistics on `bus` (which must outlive the controller).
    explicit SplatBudgetController(engine::MessageBus& bus);
    SplatBudgetController(const SplatBudgetController&) = delete;
    SplatBudgetController& operator=(const SplatBudgetController&) = delete;

    // Once per frame, before the streamer's update: the scale for its cut, from the newest statistics
    // not used yet (the last scale when none came).
    float update();
    float cut_scale() const { return scale_; }

private:
    std::optional<plugin_msgs::SplatStatistics> latest_;
    float scale_ = 1.0f;
    engine::Subscription subscription_;
};

}  // namespace splat_lod::world
