#pragma once
// The overlay's built-in panels, private to the engine's ui folder. Each draws the body of an
// ImGui window that UiOverlay has begun.
#include <string>

#include "engine/ui/frame_history.h"

namespace engine {

class Scene;
class Node;

// CPU frame time graph, a per-pass table (mean CPU and GPU ms, GPU ms graph), GL description.
void draw_frame_time_panel(const FrameHistory& history, const std::string& gl_description);

// The node hierarchy with each node's component types; a click selects a node and shows its
// local TRS and world position below the tree.
class SceneTreePanel {
public:
    void draw(const Scene* scene);
    void clear_selection() { selected_ = nullptr; }

private:
    void draw_node(const Node& node, int depth);
    static void draw_transform(const Node& node);

    // Compared by address only; dereferenced only after the tree walk of this frame met it,
    // so a node removed from the scene is never read.
    const Node* selected_ = nullptr;
    bool selected_seen_ = false;
};

}  // namespace engine
