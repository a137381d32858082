#pragma once
// What a plugin is doing in the background that the picture waits for, one line per job ("baking
// scene.ply: 42 %", "importing park.ply as a streamed world: chunks 30 %"): published by the plugin at the
// start of a frame whenever its lines change, an empty list once its last job has ended. UIs show the
// lines; tools that want the finished picture render until every source's list is empty
// (engine_render --settle).
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "plugin_msgs/detail/json_read.h"

namespace plugin_msgs {

struct BackgroundWork {
    static constexpr std::string_view kind = "background_work";

    std::string source;  // the plugin's name
    std::uint64_t frame_index = 0;
    std::vector<std::string> lines;

    bool operator==(const BackgroundWork&) const = default;
};

inline void to_json(nlohmann::json& json, const BackgroundWork& w) {
    json = nlohmann::json{{"source", w.source}, {"frame_index", w.frame_index}, {"lines", w.lines}};
}

inline void from_json(const nlohmann::json& json, BackgroundWork& w) {
    constexpr auto kind = BackgroundWork::kind;
    detail::require_object(json, kind);
    detail::only_keys(json, kind, {"source", "frame_index", "lines"});
    BackgroundWork read;
    detail::read(json, kind, "source", read.source);
    detail::read(json, kind, "frame_index", read.frame_index);
    detail::read(json, kind, "lines", read.lines);
    w = std::move(read);
}

}  // namespace plugin_msgs
