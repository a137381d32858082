// The "Splat LOD" panel: edits become LodSettings messages (valid ones only), settings published
// elsewhere show up in it, and its widgets draw in a headless ImGui frame.
#include <imgui.h>

#include <gtest/gtest.h>

#include "engine/core/message_bus.h"
#include "splat_lod/lod_panel.h"

namespace {

TEST(LodPanel, ValidEditsArePublishedInvalidOnesAreNot) {
    engine::MessageBus bus;
    std::vector<plugin_msgs::LodSettings> received;
    auto subscription =
        bus.subscribe<plugin_msgs::LodSettings>([&](const plugin_msgs::LodSettings& s) { received.push_back(s); });
    splat_lod::LodPanel panel(bus);

    plugin_msgs::LodSettings edit = panel.settings();
    EXPECT_EQ(panel.submit(edit), "");
    EXPECT_TRUE(received.empty()) << "an unchanged edit publishes nothing";

    edit.render_scale = 1.0f / 3.0f;
    edit.upscaler = plugin_msgs::Upscaler::bicubic;
    EXPECT_EQ(panel.submit(edit), "");
    ASSERT_EQ(received.size(), 1u);
    EXPECT_EQ(received.back(), edit);
    EXPECT_EQ(panel.settings(), edit);

    plugin_msgs::LodSettings bad = edit;
    bad.rule.rel_min = 2.0f;  // above rel_max
    EXPECT_NE(panel.submit(bad).find("rel_min"), std::string::npos);
    EXPECT_EQ(received.size(), 1u);
    EXPECT_EQ(panel.settings(), edit) << "the panel keeps showing the settings in force";
    EXPECT_FALSE(panel.error().empty());
}

TEST(LodPanel, FollowsSettingsAndStatisticsFromTheBus) {
    engine::MessageBus bus;
    splat_lod::LodPanel panel(bus);
    plugin_msgs::LodSettings game;
    game.rule.mode = plugin_msgs::LodMode::baseline;
    game.render_scale = 0.5f;
    bus.publish(game);
    EXPECT_EQ(panel.settings(), game);
    plugin_msgs::SplatStatistics stats;
    stats.visible = 1234;
    bus.publish(stats);
    ASSERT_TRUE(panel.statistics().has_value());
    EXPECT_EQ(panel.statistics()->visible, 1234u);
}

TEST(LodPanel, DrawsInAHeadlessFrame) {
    engine::MessageBus bus;
    splat_lod::LodPanel panel(bus);
    plugin_msgs::SplatStatistics stats;
    stats.per_level = {10, 20, 30, 40};
    bus.publish(stats);
    ImGuiContext* context = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(800, 600);
    io.IniFilename = nullptr;  // no imgui.ini in the working directory
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    for (int frame = 0; frame < 2; ++frame) {
        ImGui::NewFrame();
        ImGui::Begin(splat_lod::LodPanel::title);
        panel.draw();
        ImGui::End();
        ImGui::Render();
    }
    EXPECT_GT(ImGui::GetDrawData()->TotalVtxCount, 100);
    ImGui::DestroyContext(context);
    EXPECT_TRUE(panel.error().empty());
}

}  // namespace
