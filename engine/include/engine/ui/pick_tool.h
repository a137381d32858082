#pragma once
// Click to pick, for a windowed viewer (engine_view, the sample game): a left click that the overlay
// does not take asks the renderer what the next frame draws under the cursor (engine/render/picking.h);
// the answer, a frame or more later, is shown in the overlay's "Pick" panel (node, component, world
// point, depth) and marked on screen with a cross at the picked point, which follows the camera.
#include <cstdint>
#include <optional>

#include "engine/render/camera.h"
#include "engine/render/picking.h"

namespace engine {

class Renderer;
class UiOverlay;
class Window;

class PickTool {
public:
    // Adds the "Pick" panel to `overlay`; both must outlive the tool.
    PickTool(Renderer& renderer, UiOverlay& overlay);
    // Before the frame: a new left click on `window` with the mouse not over the overlay asks for a pick.
    void update(const Window& window, bool overlay_has_mouse);
    // After the frame, drawn from `camera`: takes an answer that has arrived (never waits for one).
    void after_frame(const CameraView& camera);

    const std::optional<PickHit>& picked() const { return picked_; }
    bool waiting() const { return pending_.has_value(); }

    static constexpr const char* panel = "Pick";

private:
    void draw_panel() const;

    Renderer& renderer_;
    std::optional<std::uint64_t> pending_;
    glm::ivec2 pending_pixel_{0}, picked_pixel_{0};
    std::optional<PickHit> picked_;
    bool answered_ = false;  // a pick has been answered (with a hit or with nothing)
    bool was_down_ = false;
    CameraView camera_;
};

}  // namespace engine
