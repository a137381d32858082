#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "overlay_panels.h"

namespace engine {
namespace {

// Scaled to the 95th percentile rather than the maximum: the first frames (shader compilation,
// uploads) are hundreds of times slower and would flatten every later frame to the axis.
float graph_top(std::vector<float> values) {
    if (values.empty()) return 1.0f;
    const auto rank = values.begin() + static_cast<std::ptrdiff_t>(0.95 * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), rank, values.end());
    return *rank * 1.25f + 1e-3f;
}

// Negative widths do not stretch plots in this ImGui version, hence the explicit width.
void plot(const char* id, const std::vector<float>& values, const char* caption, float height) {
    const float top = graph_top(values);
    ImGui::PlotLines(id, values.data(), static_cast<int>(values.size()), 0, caption, 0.0f, top,
                     ImVec2(ImGui::GetContentRegionAvail().x, height));
}

void draw_pass_row(const FrameHistory& history, const std::string& pass) {
    const std::vector<float> cpu = history.pass_cpu_ms(pass);
    const std::vector<float> gpu = history.pass_gpu_ms(pass);
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(pass.c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", static_cast<double>(FrameHistory::mean(cpu)));
    ImGui::TableNextColumn();
    // GPU timer queries are read a few frames late; until then there is nothing to show.
    if (gpu.empty())
        ImGui::TextDisabled("pending");
    else
        ImGui::Text("%.3f", static_cast<double>(FrameHistory::mean(gpu)));
    ImGui::TableNextColumn();
    ImGui::PushID(pass.c_str());
    plot("##pass_graph", gpu.empty() ? cpu : gpu, nullptr, 22.0f);
    ImGui::PopID();
}

void draw_pass_table(const FrameHistory& history) {
    const std::vector<std::string> passes = history.pass_names();
    if (passes.empty()) return;
    const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
    if (!ImGui::BeginTable("passes", 4, flags)) return;
    ImGui::TableSetupColumn("pass", ImGuiTableColumnFlags_WidthStretch, 1.2f);
    ImGui::TableSetupColumn("CPU ms", ImGuiTableColumnFlags_WidthStretch, 0.7f);
    ImGui::TableSetupColumn("GPU ms", ImGuiTableColumnFlags_WidthStretch, 0.7f);
    ImGui::TableSetupColumn("GPU ms history", ImGuiTableColumnFlags_WidthStretch, 1.6f);
    ImGui::TableHeadersRow();
    for (const auto& pass : passes) draw_pass_row(history, pass);
    ImGui::EndTable();
}

}  // namespace

void draw_frame_time_panel(const FrameHistory& history, const std::string& gl_description) {
    ImGui::TextUnformatted(gl_description.c_str());
    ImGui::Separator();
    if (history.size() == 0) {
        ImGui::TextDisabled("waiting for frame statistics");
        return;
    }
    const plugin_msgs::FrameStatistics& latest = history.frames().back();
    const std::vector<float> cpu = history.cpu_frame_ms();
    ImGui::Text("frame %llu   %d x %d", static_cast<unsigned long long>(latest.frame_index), latest.width,
                latest.height);
    char caption[96];
    std::snprintf(caption, sizeof caption, "CPU %.2f ms (mean %.2f, max %.2f)", latest.cpu_frame_ms,
                  static_cast<double>(FrameHistory::mean(cpu)), static_cast<double>(FrameHistory::max(cpu)));
    plot("##cpu_frame_ms", cpu, caption, 70.0f);
    ImGui::Text("means over the last %zu frames; GPU times from frame %lld", history.size(),
                static_cast<long long>(latest.gpu_frame_index));
    draw_pass_table(history);
}

}  // namespace engine
