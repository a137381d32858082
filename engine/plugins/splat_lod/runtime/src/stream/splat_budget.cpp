// The splat budget's controller (splat_lod/stream/splat_budget.h).
#include "splat_lod/stream/splat_budget.h"

#include "splat_lod/stream/stream_policy.h"

namespace splat_lod::world {

SplatBudgetController::SplatBudgetController(engine::MessageBus& bus)
    : subscription_(bus.subscribe<plugin_msgs::SplatStatistics>(
          [this](const plugin_msgs::SplatStatistics& statistics) { latest_ = statistics; })) {}

float SplatBudgetController::update() {
    if (latest_) {
        scale_ = next_group_cell_scale(scale_, latest_->unbudgeted, latest_->splat_budget);
        latest_.reset();
    }
    return scale_;
}

}  // namespace splat_lod::world
