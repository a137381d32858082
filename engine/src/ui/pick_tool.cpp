// Click to pick (engine/ui/pick_tool.h).
#include "engine/ui/pick_tool.h"

#include <imgui.h>

#include <string>

#include "engine/platform/window.h"
#include "engine/render/renderer.h"
#include "engine/scene/component.h"
#include "engine/scene/node.h"
#include "engine/ui/overlay.h"

namespace engine {

PickTool::PickTool(Renderer& renderer, UiOverlay& overlay) : renderer_(renderer) {
    overlay.add_panel(panel, [this] { draw_panel(); });
}

void PickTool::update(const Window& window, bool overlay_has_mouse) {
    const bool down = window.mouse_down(MouseButton::left);
    if (down && !was_down_ && !overlay_has_mouse) {
        pending_pixel_ = glm::ivec2(glm::floor(window.cursor_pixel()));
        pending_ = renderer_.pick(pending_pixel_);
    }
    was_down_ = down;
}

void PickTool::after_frame(const CameraView& camera) {
    camera_ = camera;
    if (!pending_) return;
    const PickResult result = renderer_.pick_result(*pending_);
    if (!result.ready) return;
    picked_ = result.hit;
    picked_pixel_ = pending_pixel_;
    answered_ = true;
    pending_.reset();
}

void PickTool::draw_panel() const {
    if (!answered_) {
        ImGui::TextUnformatted(pending_ ? "picking..." : "left click to pick a point");
        return;
    }
    if (!picked_) {
        ImGui::Text("pixel %d, %d: nothing", picked_pixel_.x, picked_pixel_.y);
        return;
    }
    const PickHit& hit = *picked_;
    ImGui::Text("pixel %d, %d", picked_pixel_.x, picked_pixel_.y);
    ImGui::Text("node: %s", hit.node->name().c_str());
    ImGui::Text("component: %s", std::string(hit.component->type_name()).c_str());
    ImGui::Text("world: %.3f, %.3f, %.3f", hit.position.x, hit.position.y, hit.position.z);
    ImGui::Text("depth: %.3f", hit.depth);
    // The cross at the picked point as the camera sees it now (none when it is behind the camera).
    const glm::vec3 pixel = camera_.project_to_pixel(glm::vec3(hit.position));
    if (!(pixel.z > 0.0f)) return;
    const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;  // framebuffer pixels per ImGui unit
    const ImVec2 p(pixel.x / scale.x, pixel.y / scale.y);
    const float r = 8.0f;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    for (const auto& [colour, width] :
         {std::pair{IM_COL32(0, 0, 0, 255), 4.0f}, {IM_COL32(255, 255, 255, 255), 2.0f}}) {
        draw->AddLine(ImVec2(p.x - r, p.y), ImVec2(p.x + r, p.y), colour, width);
        draw->AddLine(ImVec2(p.x, p.y - r), ImVec2(p.x, p.y + r), colour, width);
    }
}

}  // namespace engine
