#include <imgui.h>

#include <string>

#include <glm/gtc/quaternion.hpp>

#include "engine/scene/scene.h"
#include "overlay_panels.h"

namespace engine {
namespace {

// "name  [mesh, camera]": the node and the scene-file type names of its components.
std::string node_label(const Node& node) {
    std::string label = node.name().empty() ? std::string("(unnamed)") : node.name();
    if (node.components().empty()) return label;
    label += "  [";
    bool first = true;
    for (const auto& component : node.components()) {
        if (!first) label += ", ";
        label += component->type_name();
        first = false;
    }
    return label + "]";
}

void show_vec3(const char* label, const glm::vec3& v) {
    ImGui::Text("%-12s %9.3f %9.3f %9.3f", label, static_cast<double>(v.x), static_cast<double>(v.y),
                static_cast<double>(v.z));
}

}  // namespace

void SceneTreePanel::draw(const Scene* scene) {
    if (scene == nullptr) {
        ImGui::TextDisabled("no scene");
        return;
    }
    if (!scene->source_file.empty()) ImGui::TextUnformatted(scene->source_file.filename().string().c_str());
    selected_seen_ = false;
    const float tree_height = selected_ != nullptr ? ImGui::GetContentRegionAvail().y * 0.6f : 0.0f;
    ImGui::BeginChild("tree", ImVec2(0.0f, tree_height), true);
    for (const auto& child : scene->root().children()) draw_node(*child, 0);
    ImGui::EndChild();
    if (!selected_seen_) selected_ = nullptr;
    if (selected_ != nullptr) draw_transform(*selected_);
}

void SceneTreePanel::draw_node(const Node& node, int depth) {
    if (&node == selected_) selected_seen_ = true;
    ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_OpenOnArrow | ImGuiTreeNodeFlags_SpanAvailWidth;
    if (node.children().empty()) flags |= ImGuiTreeNodeFlags_Leaf | ImGuiTreeNodeFlags_NoTreePushOnOpen;
    if (&node == selected_) flags |= ImGuiTreeNodeFlags_Selected;
    if (depth < 2) flags |= ImGuiTreeNodeFlags_DefaultOpen;
    const bool open = ImGui::TreeNodeEx(static_cast<const void*>(&node), flags, "%s", node_label(node).c_str());
    if (ImGui::IsItemClicked() && !ImGui::IsItemToggledOpen()) {
        selected_ = &node;
        selected_seen_ = true;
    }
    if (!open || node.children().empty()) return;
    for (const auto& child : node.children()) draw_node(*child, depth + 1);
    ImGui::TreePop();
}

void SceneTreePanel::draw_transform(const Node& node) {
    const Transform& t = node.transform();
    ImGui::TextUnformatted(node.name().c_str());
    show_vec3("translation", t.translation);
    ImGui::Text("%-12s %9.3f %9.3f %9.3f %9.3f", "rot (wxyz)", static_cast<double>(t.rotation.w),
                static_cast<double>(t.rotation.x), static_cast<double>(t.rotation.y),
                static_cast<double>(t.rotation.z));
    show_vec3("euler (deg)", glm::degrees(glm::eulerAngles(t.rotation)));
    show_vec3("scale", t.scale);
    show_vec3("world pos", glm::vec3(node.world_matrix()[3]));
}

}  // namespace engine
