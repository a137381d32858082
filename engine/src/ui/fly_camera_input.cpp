// Fly camera input from a window (engine/ui/fly_camera_input.h).
#include "engine/ui/fly_camera_input.h"

#include "engine/platform/window.h"

namespace engine {

FlyCameraInput read_fly_camera_input(const Window& window, bool ui_has_mouse, bool ui_has_keyboard) {
    FlyCameraInput input;
    if (!ui_has_keyboard) {
        input.forward = window.key_down(Key::w);
        input.back = window.key_down(Key::s);
        input.left = window.key_down(Key::a);
        input.right = window.key_down(Key::d);
        input.up = window.key_down(Key::e);
        input.down = window.key_down(Key::q);
        input.fast = window.key_down(Key::left_shift);
    }
    if (!ui_has_mouse) {
        input.look = window.mouse_down(MouseButton::right);
        input.mouse_delta = window.mouse_delta();
        input.scroll = window.scroll_delta();
    }
    return input;
}

}  // namespace engine
