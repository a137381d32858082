#pragma once
// What the drop-in LOD ("lod": "auto") is doing in the background, one line per component that has
// work left ("baking scene.ply: 42 %", "importing park.ply as a streamed world: binning 30 %"):
// published by the splat plugin at the start of a frame whenever the lines change (an empty list once
// the last job ends), shown by the LOD panel.
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "plugin_msgs/detail/json_read.h"

namespace plugin_msgs {

struct DropInLodStatus {
    static constexpr std::string_view kind = "drop_in_lod_status";

    std::uint64_t frame_index = 0;
    std::vector<std::string> lines;
};

inline void to_json(nlohmann::json& json, const DropInLodStatus& s) {
    json = nlohmann::json{{"frame_index", s.frame_index}, {"lines", s.lines}};
}

inline void from_json(const nlohmann::json& json, DropInLodStatus& s) {
    constexpr auto kind = DropInLodStatus::kind;
    detail::require_object(json, kind);
    detail::only_keys(json, kind, {"frame_index", "lines"});
    DropInLodStatus read;
    detail::read(json, kind, "frame_index", read.frame_index);
    detail::read(json, kind, "lines", read.lines);
    s = std::move(read);
}

}  // namespace plugin_msgs
