#pragma once
// The fly camera's input from a window (ui/fly_camera.h, platform/window.h): W/A/S/D, E/Q and Shift
// unless the UI has the keyboard, the right mouse button, its motion and the wheel unless the UI has
// the mouse. Shared by the windowed tools so that every window flies the same way.
#include "engine/ui/fly_camera.h"

namespace engine {

class Window;

FlyCameraInput read_fly_camera_input(const Window& window, bool ui_has_mouse, bool ui_has_keyboard);

}  // namespace engine
