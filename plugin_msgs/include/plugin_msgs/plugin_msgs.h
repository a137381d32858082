#pragma once
// Every typed message between the engine and its plugins. Each is a plain struct with a
// `static constexpr std::string_view kind` (the engine::MessageBus key), a defaulted
// operator== and a JSON round trip; header-only, with no GL and no engine dependency.
#include "plugin_msgs/camera_state.h"
#include "plugin_msgs/frame_statistics.h"
#include "plugin_msgs/lod_settings.h"
#include "plugin_msgs/splat_statistics.h"
#include "plugin_msgs/stream_events.h"
