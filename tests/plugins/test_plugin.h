#pragma once
// A minimal plugin for the plugin manager tests: "test_plugin" registers the component type
// "test_marker" and the render pass "test_plugin.pass". Built as a static library (this
// factory) and as loadable modules (see CMakeLists.txt).
#include <memory>

#include "engine/plugin/plugin.h"

std::unique_ptr<engine::Plugin> make_test_plugin();
