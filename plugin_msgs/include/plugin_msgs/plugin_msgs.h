#pragma once
// Every typed message of the engine itself. Each is a plain struct with a `static constexpr
// std::string_view kind` (the engine::MessageBus key), a defaulted operator== and a JSON round trip;
// header-only, with no GL and no engine dependency. A plugin's own messages follow the same pattern
// (plugin_msgs/detail/ has the JSON helpers) and live in the plugin's folder, e.g. splat_lod's in
// engine/plugins/splat_lod/msgs/include/splat_lod/msgs/.
#include "plugin_msgs/background_work.h"
#include "plugin_msgs/camera_state.h"
#include "plugin_msgs/frame_statistics.h"
