#include "sample_game/streaming_panel.h"

#include <imgui.h>

#include <algorithm>
#include <vector>

#include "sample_game/game_settings.h"

namespace sample_game {
namespace {

float mib(std::uint64_t bytes) {
    return static_cast<float>(static_cast<double>(bytes) / static_cast<double>(kMiB));
}

// A bar filled to value / limit, red once the value is over the limit.
void budget_bar(float value, float limit, const char* unit) {
    const float fraction = limit > 0.0f ? value / limit : 0.0f;
    char text[64];
    std::snprintf(text, sizeof text, "%.1f / %.1f %s", static_cast<double>(value), static_cast<double>(limit), unit);
    const bool over = fraction > 1.0f;
    if (over) ImGui::PushStyleColor(ImGuiCol_PlotHistogram, ImVec4(0.85f, 0.25f, 0.2f, 1.0f));
    ImGui::ProgressBar(std::min(fraction, 1.0f), ImVec2(-1.0f, 0.0f), text);
    if (over) ImGui::PopStyleColor();
}

}  // namespace

StreamingPanel::StreamingPanel(engine::MessageBus& bus) {
    events_ = bus.subscribe<plugin_msgs::StreamEvent>([this](const plugin_msgs::StreamEvent& e) {
        if (e.event != plugin_msgs::StreamEventType::failed) return;
        ++failures_seen_;
        failures_.push_back({e.chunk_id, e.message});
        while (failures_.size() > kFailuresKept) failures_.pop_front();
    });
}

void StreamingPanel::record(const StreamingSnapshot& snapshot) {
    latest_ = snapshot;
    frame_ms_.push_back(static_cast<float>(snapshot.frame_ms));
    while (frame_ms_.size() > kHistory) frame_ms_.pop_front();
}

bool StreamingPanel::draw(int& memory_budget_mib, float& upload_budget_mib) {
    const StreamingSnapshot& s = latest_;
    const std::vector<float> times(frame_ms_.begin(), frame_ms_.end());
    const float newest = times.empty() ? 0.0f : times.back();
    const float worst = times.empty() ? 1.0f : *std::max_element(times.begin(), times.end());
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "%.1f ms (max %.1f)", static_cast<double>(newest),
                  static_cast<double>(worst));
    ImGui::PlotLines("frame", times.data(), static_cast<int>(times.size()), 0, overlay, 0.0f, worst * 1.1f,
                     ImVec2(0.0f, 60.0f));

    ImGui::TextWrapped(
        "chunks %zu (by the least advanced level they need): resident %u, partial %u, loaded %u, requested %u, absent "
        "%u",
        s.chunk_count, s.chunks.resident, s.chunks.partial, s.chunks.loaded, s.chunks.requested, s.chunks.absent);
    ImGui::Text("finest level resident: L1 %u  L2 %u  L3 %u  L4 %u  none %u", s.chunks.finest_resident[1],
                s.chunks.finest_resident[2], s.chunks.finest_resident[3], s.chunks.finest_resident[4],
                s.chunks.finest_resident[0]);
    ImGui::Text("LOD cut: %u chunks and %u of %zu chunk groups drawn (%u groups resident)", s.chunks_drawn,
                s.groups_drawn, s.group_count, s.groups_resident);
    ImGui::TextUnformatted("resident GPU memory");
    budget_bar(mib(s.resident_bytes), mib(s.memory_budget_bytes), "MiB");
    ImGui::TextUnformatted("uploaded this frame");
    budget_bar(mib(s.upload_bytes), mib(s.upload_budget_bytes), "MiB");
    bool changed = ImGui::SliderInt("memory budget (MiB)", &memory_budget_mib, 16, 4096);
    changed = ImGui::SliderFloat("upload budget (MiB/frame)", &upload_budget_mib, 0.25f, 64.0f, "%.2f") || changed;

    ImGui::Separator();
    if (failures_seen_ == 0) {
        ImGui::TextUnformatted("no chunk failures");
        return changed;
    }
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f),
                       "%llu chunk failures (newest last):", static_cast<unsigned long long>(failures_seen_));
    for (const auto& f : failures_) ImGui::TextWrapped("%s: %s", f.chunk_id.c_str(), f.message.c_str());
    return changed;
}

}  // namespace sample_game
