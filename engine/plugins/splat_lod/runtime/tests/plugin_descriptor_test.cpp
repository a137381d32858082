// The plugin's descriptor (engine/plugins/splat_lod/plugin.json) against the plugin itself, so that
// neither can drift from the other: name, version, shader folder and the settings' defaults.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/plugin/plugin.h"
#include "splat_lod/msgs/lod_settings.h"
#include "splat_lod/splat_lod_plugin.h"
#include "test_support.h"

TEST(PluginDescriptor, SaysWhatThePluginIs) {
    const auto file = engine::test::repo_dir() / "engine/plugins/splat_lod/plugin.json";
    std::ifstream in(file);
    ASSERT_TRUE(in) << file;
    const auto descriptor = nlohmann::json::parse(in);
    const auto plugin = splat_lod::make_plugin();
    EXPECT_EQ(descriptor.at("name").get<std::string>(), plugin->name());
    EXPECT_EQ(descriptor.at("version").get<std::string>(), plugin->version());
    const std::filesystem::path shaders = file.parent_path() / descriptor.at("shaders").get<std::string>();
    EXPECT_TRUE(std::filesystem::exists(shaders / "splat_lod" / "splat_tile_raster.comp.glsl")) << shaders;
    EXPECT_EQ(std::filesystem::canonical(shaders), std::filesystem::canonical(splat_lod::shader_dir()))
        << "the plugin's shader folder unless SPLAT_LOD_SHADER_DIR says otherwise";
    EXPECT_EQ(descriptor.at("settings_message").get<std::string>(), plugin_msgs::LodSettings::kind);
    EXPECT_EQ(descriptor.at("default_settings").get<plugin_msgs::LodSettings>(), plugin_msgs::LodSettings{});
    EXPECT_EQ(descriptor.at("default_settings"), nlohmann::json(plugin_msgs::LodSettings{})) << "every key listed";
}
