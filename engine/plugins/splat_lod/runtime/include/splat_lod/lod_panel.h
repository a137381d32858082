#pragma once
// The "Splat LOD" panel of the ImGui overlay: the LOD mode and thresholds, render scale and
// upscaler, mip filter and level colouring, plus the newest frame's statistics (Gaussians per
// level, skipped, tile-splat pairs, GPU memory) and what the drop-in LOD is doing in the background. Edits are
// published as plugin_msgs::LodSettings, so the panel drives the splat pass the same way tools and games do; settings
// published by anyone else show up in the panel.
#include <optional>
#include <string>
#include <vector>

#include "plugin_msgs/background_work.h"
#include "splat_lod/msgs/lod_settings.h"
#include "splat_lod/msgs/splat_statistics.h"

#include "engine/core/message_bus.h"

namespace engine {
class UiOverlay;
}

namespace splat_lod {

class LodPanel {
public:
    static constexpr const char* title = "Splat LOD";

    explicit LodPanel(engine::MessageBus& bus, const plugin_msgs::LodSettings& initial = {});

    // The panel's widgets (call inside an ImGui window, with the overlay's context current).
    void draw();

    // What an edit does: publishes `edited` when it is valid and differs from the settings shown;
    // an invalid edit is not published and its reason is kept for display. Returns that reason
    // (empty when published or unchanged).
    std::string submit(const plugin_msgs::LodSettings& edited);

    const plugin_msgs::LodSettings& settings() const { return settings_; }
    const std::string& error() const { return error_; }
    const std::optional<plugin_msgs::SplatStatistics>& statistics() const { return statistics_; }
    // The drop-in LOD's background work, as last published (plugin_msgs::BackgroundWork).
    const std::vector<std::string>& drop_in_lines() const { return drop_in_lines_; }

private:
    engine::MessageBus& bus_;
    plugin_msgs::LodSettings settings_;
    std::string error_;
    std::optional<plugin_msgs::SplatStatistics> statistics_;
    std::vector<std::string> drop_in_lines_;
    engine::Subscription settings_subscription_, statistics_subscription_, drop_in_subscription_;
};

// Adds the panel to `overlay` (which must outlive neither `bus` nor the returned panel's use).
void add_lod_panel(engine::UiOverlay& overlay, engine::MessageBus& bus);

}  // namespace splat_lod
