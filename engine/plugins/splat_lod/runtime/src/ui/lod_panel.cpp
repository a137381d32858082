#include "splat_lod/lod_panel.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "engine/ui/overlay.h"

namespace splat_lod {
namespace {

template <typename E, std::size_t N>
bool enum_combo(const char* label, E& value, const std::array<std::string_view, N>& names) {
    bool changed = false;
    const std::string current(names[static_cast<std::size_t>(value)]);
    if (ImGui::BeginCombo(label, current.c_str())) {
        for (std::size_t i = 0; i < N; ++i) {
            const std::string name(names[i]);
            if (ImGui::Selectable(name.c_str(), i == static_cast<std::size_t>(value))) {
                value = static_cast<E>(i);
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

}  // namespace

LodPanel::LodPanel(engine::MessageBus& bus, const plugin_msgs::LodSettings& initial) : bus_(bus), settings_(initial) {
    settings_subscription_ = bus.subscribe<plugin_msgs::LodSettings>([this](const plugin_msgs::LodSettings& s) {
        settings_ = s;
        error_.clear();
    });
    statistics_subscription_ =
        bus.subscribe<plugin_msgs::SplatStatistics>([this](const plugin_msgs::SplatStatistics& s) { statistics_ = s; });
    drop_in_subscription_ = bus.subscribe<plugin_msgs::BackgroundWork>(
        [this](const plugin_msgs::BackgroundWork& w) { drop_in_lines_ = w.lines; });
}

std::string LodPanel::submit(const plugin_msgs::LodSettings& edited) {
    if (edited == settings_) return {};
    error_ = edited.validate();
    if (!error_.empty()) return error_;
    bus_.publish(edited);  // our own subscription takes it as the settings shown
    settings_ = edited;
    return {};
}

void LodPanel::draw() {
    plugin_msgs::LodSettings edit = settings_;
    plugin_msgs::LodRule& rule = edit.rule;
    enum_combo("mode", rule.mode, plugin_msgs::kLodModeNames);
    ImGui::DragFloat("S_T (px)", &rule.size_threshold_px, 0.05f, 0.1f, 64.0f, "%.2f");
    ImGui::DragFloat("rel min", &rule.rel_min, 0.01f, 0.01f, 8.0f, "%.2f");
    ImGui::DragFloat("rel max", &rule.rel_max, 0.01f, 0.01f, 8.0f, "%.2f");
    ImGui::DragFloat("transition band (octaves, 0: hard)", &rule.transition_band, 0.005f, 0.0f,
                     plugin_msgs::LodRule::kMaxTransitionBand, "%.4f");
    enum_combo("transition placement", rule.transition_placement, plugin_msgs::kTransitionPlacementNames);
    ImGui::DragFloat("overlapping levels' band (auto)", &rule.overlap_transition_band, 0.01f, 0.0f,
                     plugin_msgs::LodRule::kMaxTransitionBand, "%.3f");
    ImGui::Checkbox("mip filter", &edit.mip_filter);
    ImGui::Checkbox("level colouring", &edit.level_colouring);
    // The splat budget in thousands of Gaussians per frame (0: none).
    int budget_k = static_cast<int>(edit.splat_budget / 1000);
    if (ImGui::DragInt("splat budget (k, 0: none)", &budget_k, 5.0f, 0, 100000))
        edit.splat_budget = static_cast<std::uint32_t>(std::max(budget_k, 0)) * 1000u;
    ImGui::Separator();
    // Render scale as its inverse, the upscaling factor: 1 is native, 3 renders a third as wide.
    float factor = 1.0f / edit.render_scale;
    if (ImGui::SliderFloat("upscale factor", &factor, 1.0f, 8.0f, "%.2fx")) edit.render_scale = 1.0f / factor;
    ImGui::TextUnformatted("presets");
    for (const float preset : {1.0f, 2.0f, 3.0f, 4.0f}) {
        ImGui::SameLine();
        const std::string label = std::to_string(static_cast<int>(preset)) + "x";
        if (ImGui::SmallButton(label.c_str())) edit.render_scale = 1.0f / preset;
    }
    enum_combo("upscaler", edit.upscaler, plugin_msgs::kUpscalerNames);
    submit(edit);
    if (!error_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "%s", error_.c_str());
    for (const std::string& line : drop_in_lines_) ImGui::TextUnformatted(line.c_str());  // "lod": "auto"

    ImGui::Separator();
    if (!statistics_) {
        ImGui::TextUnformatted("no splats drawn yet");
        return;
    }
    const auto& s = *statistics_;
    ImGui::Text("visible %llu of %llu, culled %llu, skipped %llu", static_cast<unsigned long long>(s.visible),
                static_cast<unsigned long long>(s.considered), static_cast<unsigned long long>(s.culled),
                static_cast<unsigned long long>(s.skipped));
    if (s.splat_budget > 0)
        ImGui::Text("budget %llu: would draw %llu; threshold %.2f px (x%.2f)%s",
                    static_cast<unsigned long long>(s.splat_budget), static_cast<unsigned long long>(s.unbudgeted),
                    s.budget_threshold_px, s.budget_scale, s.budget_coverage_cut_px > 0.0 ? ", smallest dropped" : "");
    ImGui::Text("per level  %llu / %llu / %llu / %llu", static_cast<unsigned long long>(s.per_level[0]),
                static_cast<unsigned long long>(s.per_level[1]), static_cast<unsigned long long>(s.per_level[2]),
                static_cast<unsigned long long>(s.per_level[3]));
    ImGui::Text("tile-splat pairs %llu (capacity %llu)%s", static_cast<unsigned long long>(s.tile_splat_pairs),
                static_cast<unsigned long long>(s.key_capacity), s.overflowed ? ", overflowed" : "");
    ImGui::Text("GPU memory %.1f MiB", static_cast<double>(s.resident_bytes) / (1024.0 * 1024.0));
}

void add_lod_panel(engine::UiOverlay& overlay, engine::MessageBus& bus) {
    auto panel = std::make_shared<LodPanel>(bus);
    ImGuiContext* context = overlay.imgui_context();
    // This library links its own copy of Dear ImGui: draw into the overlay's context.
    overlay.add_panel(LodPanel::title, [panel, context] {
        ImGui::SetCurrentContext(context);
        panel->draw();
    });
}

}  // namespace splat_lod
