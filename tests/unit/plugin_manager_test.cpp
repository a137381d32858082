#include <algorithm>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/engine.h"
#include "engine/plugin/plugin_abi.h"
#include "test_plugin.h"

using engine::Engine;

namespace {

const std::string kSharedPlugin = TEST_PLUGIN_SHARED_PATH;
const std::string kBadAbiPlugin = TEST_PLUGIN_BAD_ABI_PATH;
const std::string kOldStringAbiPlugin = TEST_PLUGIN_OLD_STRING_ABI_PATH;

bool has_pass(Engine& engine, const std::string& name) {
    const auto names = engine.renderer().pass_names();
    return std::find(names.begin(), names.end(), name) != names.end();
}

bool registered(Engine& engine) {
    return engine.components().contains("test_marker") || has_pass(engine, "test_plugin.pass");
}

bool fully_registered(Engine& engine) {
    return engine.components().contains("test_marker") && has_pass(engine, "test_plugin.pass");
}

// The engine::Error message `action` throws; empty when it does not throw.
std::string error_of(const std::function<void()>& action) {
    try {
        action();
    } catch (const engine::Error& e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// Creates a test_marker component the way the scene loader does and returns its type name.
std::string create_marker(Engine& engine) {
    engine::ComponentLoadContext context{"scene.json", "nodes[0].components[0]", &engine.assets()};
    const auto component =
        engine.components().create("test_marker", {{"type", "test_marker"}, {"label", "x"}}, context);
    return std::string(component->type_name());
}

// Writes "startup <name>" and "shutdown <name>" into a shared journal.
class JournalPlugin final : public engine::Plugin {
public:
    JournalPlugin(std::string name, std::vector<std::string>& journal) : name_(std::move(name)), journal_(journal) {}
    std::string name() const override { return name_; }
    std::string version() const override { return "0"; }
    void startup(engine::PluginContext&) override { journal_.push_back("startup " + name_); }
    void shutdown(engine::PluginContext&) override { journal_.push_back("shutdown " + name_); }

private:
    std::string name_;
    std::vector<std::string>& journal_;
};

// Registers a component type and a pass, then fails (or, at shutdown, forgets to remove them).
class CarelessPlugin final : public engine::Plugin {
public:
    explicit CarelessPlugin(bool fail_startup) : fail_startup_(fail_startup) {}
    std::string name() const override { return "careless"; }
    std::string version() const override { return "0"; }
    void startup(engine::PluginContext& context) override {
        auto original = make_test_plugin();
        original->startup(context);
        if (fail_startup_) throw std::runtime_error("out of coffee");
    }
    void shutdown(engine::PluginContext&) override {}

private:
    bool fail_startup_;
};

}  // namespace

TEST(PluginManager, StaticPluginRegistersAndUnregisters) {
    Engine engine;
    ASSERT_FALSE(registered(engine));
    engine::Plugin& plugin = engine.plugins().add_static(make_test_plugin());
    EXPECT_EQ(plugin.name(), "test_plugin");
    EXPECT_TRUE(fully_registered(engine));
    EXPECT_EQ(create_marker(engine), "test_marker");
    EXPECT_EQ(engine.plugins().names(), std::vector<std::string>{"test_plugin"});
    EXPECT_EQ(engine.plugins().find("test_plugin"), &plugin);

    engine.plugins().unload("test_plugin");
    EXPECT_FALSE(registered(engine));
    EXPECT_TRUE(engine.plugins().names().empty());
    EXPECT_EQ(engine.plugins().find("test_plugin"), nullptr);
}

TEST(PluginManager, SharedPluginRegistersAndUnregisters) {
    Engine engine;
    engine::Plugin& plugin = engine.plugins().load_shared(kSharedPlugin);
    EXPECT_EQ(plugin.name(), "test_plugin");
    EXPECT_EQ(plugin.version(), "1.0.0");
    EXPECT_TRUE(fully_registered(engine));
    EXPECT_EQ(create_marker(engine), "test_marker");  // the factory's code is in the library

    engine.plugins().unload("test_plugin");
    EXPECT_FALSE(registered(engine));
}

TEST(PluginManager, SharedPluginReloadsAfterUnload) {
    Engine engine;
    for (int round = 0; round < 3; ++round) {
        engine.plugins().load_shared(kSharedPlugin);
        EXPECT_TRUE(fully_registered(engine)) << "round " << round;
        engine.plugins().unload("test_plugin");
        EXPECT_FALSE(registered(engine)) << "round " << round;
    }
}

TEST(PluginManager, SharedPluginIsShutDownWithTheEngine) {
    auto engine = std::make_unique<Engine>();
    engine->plugins().load_shared(kSharedPlugin);
    engine.reset();  // must destroy the plugin before closing its library, without crashing
    SUCCEED();
}

TEST(PluginManager, RejectsBadAbiVersionNamingFileAndBothVersions) {
    Engine engine;
    const std::string error = error_of([&] { engine.plugins().load_shared(kBadAbiPlugin); });
    EXPECT_TRUE(contains(error, kBadAbiPlugin)) << error;
    EXPECT_TRUE(contains(error, "ABI version 999")) << error;
    EXPECT_TRUE(contains(error, "engine's " + std::to_string(ENGINE_PLUGIN_ABI_VERSION))) << error;
    EXPECT_FALSE(registered(engine));
    EXPECT_TRUE(engine.plugins().names().empty());
}

TEST(PluginManager, RejectsOtherStdStringAbiNamingTheDifference) {
    Engine engine;
    const std::string error = error_of([&] { engine.plugins().load_shared(kOldStringAbiPlugin); });
    EXPECT_TRUE(contains(error, kOldStringAbiPlugin)) << error;
    EXPECT_TRUE(contains(error, "_GLIBCXX_USE_CXX11_ABI): plugin 0, engine 1")) << error;
    EXPECT_TRUE(contains(error, "sizeof(std::string): plugin 8, engine 32")) << error;
    EXPECT_TRUE(engine.plugins().names().empty());
}

TEST(PluginManager, MissingLibraryIsAClearError) {
    Engine engine;
    const std::string path = "/nonexistent/folder/no_such_plugin.so";
    const std::string error = error_of([&] { engine.plugins().load_shared(path); });
    EXPECT_TRUE(contains(error, path)) << error;
    EXPECT_TRUE(contains(error, "no such file")) << error;
}

TEST(PluginManager, LibraryWithoutEntryPointsIsAClearError) {
    Engine engine;
    const std::string path = TEST_ENGINE_LIBRARY_PATH;  // a loadable library that is not a plugin
    const std::string error = error_of([&] { engine.plugins().load_shared(path); });
    EXPECT_TRUE(contains(error, path)) << error;
    EXPECT_TRUE(contains(error, "missing symbol 'engine_plugin_abi_version'")) << error;
}

TEST(PluginManager, RejectsDuplicateNames) {
    Engine engine;
    engine.plugins().add_static(make_test_plugin());
    const std::string shared_error = error_of([&] { engine.plugins().load_shared(kSharedPlugin); });
    EXPECT_TRUE(contains(shared_error, kSharedPlugin)) << shared_error;
    EXPECT_TRUE(contains(shared_error, "'test_plugin' (version 1.0.0) is already loaded")) << shared_error;
    const std::string static_error = error_of([&] { engine.plugins().add_static(make_test_plugin()); });
    EXPECT_TRUE(contains(static_error, "already loaded")) << static_error;
    // The first plugin is untouched.
    EXPECT_EQ(engine.plugins().names(), std::vector<std::string>{"test_plugin"});
    EXPECT_TRUE(fully_registered(engine));
}

TEST(PluginManager, ShutsDownInReverseOrderOfStartup) {
    std::vector<std::string> journal;
    {
        Engine engine;
        for (const char* name : {"first", "second", "third"})
            engine.plugins().add_static(std::make_unique<JournalPlugin>(name, journal));
        EXPECT_EQ(engine.plugins().names(), (std::vector<std::string>{"first", "second", "third"}));
        engine.plugins().shutdown_all();
        EXPECT_TRUE(engine.plugins().names().empty());
        engine.plugins().add_static(std::make_unique<JournalPlugin>("a", journal));
        engine.plugins().add_static(std::make_unique<JournalPlugin>("b", journal));
    }  // the engine's destructor shuts down what is left
    EXPECT_EQ(journal, (std::vector<std::string>{"startup first", "startup second", "startup third", "shutdown third",
                                                 "shutdown second", "shutdown first", "startup a", "startup b",
                                                 "shutdown b", "shutdown a"}));
}

TEST(PluginManager, FailedStartupLeavesNothingRegistered) {
    Engine engine;
    const std::string error = error_of([&] { engine.plugins().add_static(std::make_unique<CarelessPlugin>(true)); });
    EXPECT_TRUE(contains(error, "plugin 'careless': startup failed: out of coffee")) << error;
    EXPECT_FALSE(registered(engine));
    EXPECT_TRUE(engine.plugins().names().empty());
}

TEST(PluginManager, RemovesWhatShutdownForgot) {
    Engine engine;
    engine.plugins().add_static(std::make_unique<CarelessPlugin>(false));
    EXPECT_TRUE(fully_registered(engine));
    engine.plugins().unload("careless");
    EXPECT_FALSE(registered(engine));
}

TEST(PluginManager, UnloadOfUnknownNameNamesTheLoadedOnes) {
    Engine engine;
    engine.plugins().add_static(make_test_plugin());
    const std::string error = error_of([&] { engine.plugins().unload("nope"); });
    EXPECT_TRUE(contains(error, "no plugin named 'nope' (loaded: test_plugin)")) << error;
}
