#include "engine/plugin/plugin_manager.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <exception>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/plugin/plugin_abi.h"
#include "engine/render/renderer.h"
#include "engine/scene/component_registry.h"

namespace engine {

namespace {

struct LibraryCloser {
    void operator()(void* handle) const { dlclose(handle); }
};
using LibraryHandle = std::unique_ptr<void, LibraryCloser>;

using PluginDeleter = void (*)(Plugin*);
void delete_linked_plugin(Plugin* plugin) {
    delete plugin;
}

// What a plugin's startup added, found by comparing the registries before and after it. The
// manager can then guarantee that a failed startup or a forgetful shutdown leaves nothing
// behind, which matters most for shared plugins: a factory or pass left registered after
// dlclose() would call into unmapped code.
struct Registrations {
    std::vector<std::string> component_types;
    std::vector<std::string> passes;
};

Registrations snapshot(const PluginContext& context) {
    return {context.components.types(), context.renderer.pass_names()};
}

std::vector<std::string> added(std::vector<std::string> before, std::vector<std::string> after) {
    std::sort(before.begin(), before.end());
    std::sort(after.begin(), after.end());
    std::vector<std::string> out;
    std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(out));
    return out;
}

Registrations added(const Registrations& before, const Registrations& after) {
    return {added(before.component_types, after.component_types), added(before.passes, after.passes)};
}

// Removes what is still registered and returns it, so that callers can warn about it.
std::vector<std::string> remove_remaining(const Registrations& registrations, PluginContext& context) {
    std::vector<std::string> removed;
    for (const auto& type : registrations.component_types) {
        if (!context.components.contains(type)) continue;
        context.components.remove(type);
        removed.push_back("component type '" + type + "'");
    }
    const auto passes = context.renderer.pass_names();
    for (const auto& pass : registrations.passes) {
        if (std::find(passes.begin(), passes.end(), pass) == passes.end()) continue;
        context.renderer.remove_pass(pass);
        removed.push_back("render pass '" + pass + "'");
    }
    return removed;
}

std::string join(const std::vector<std::string>& items, const std::string& separator = ", ") {
    std::string out;
    for (const auto& item : items) out += (out.empty() ? "" : separator) + item;
    return out;
}

// Runs `action`, turning any exception into its message; empty when it succeeded.
template <class Action>
std::string error_of(Action&& action) {
    try {
        action();
    } catch (const std::exception& e) {
        return e.what();
    } catch (...) {
        return "an exception not derived from std::exception";
    }
    return {};
}

}  // namespace

// One started plugin. Member order matters: the plugin object, whose code may live in the
// library, is destroyed (by the library's own destroy function) before the library is closed.
struct PluginManager::Loaded {
    std::filesystem::path library;  // empty for a plugin linked into the executable
    LibraryHandle handle;
    std::unique_ptr<Plugin, PluginDeleter> plugin{nullptr, delete_linked_plugin};
    std::string name;
    Registrations registrations;

    ~Loaded() {
        plugin.reset();
        handle.reset();
    }

    // "plugin 'name'" or "plugin library '<path>'", to start messages with.
    std::string describe() const {
        if (library.empty()) return "plugin '" + name + "'";
        return "plugin library '" + library.string() + "'" + (name.empty() ? "" : " ('" + name + "')");
    }

    // Starts the plugin; on failure undoes whatever it registered and returns the reason.
    std::string startup(PluginContext& context) {
        const Registrations before = snapshot(context);
        std::string error = error_of([&] { plugin->startup(context); });
        registrations = added(before, snapshot(context));
        if (!error.empty()) remove_remaining(registrations, context);
        return error;
    }

    // Shuts the plugin down and removes what it left registered; returns the reason it failed.
    std::string shutdown(PluginContext& context) {
        const std::string error = error_of([&] { plugin->shutdown(context); });
        const auto leftovers = remove_remaining(registrations, context);
        if (!leftovers.empty())
            log_warning(describe() + " left " + join(leftovers) + " registered at shutdown; removed them");
        return error;
    }
};

namespace {

template <class Function>
Function find_symbol(void* handle, const char* symbol, const std::string& where) {
    void* address = dlsym(handle, symbol);
    if (address == nullptr)
        fail(where + ": missing symbol '" + symbol + "' (not an engine plugin, or ENGINE_EXPORT_PLUGIN is missing)");
    // POSIX guarantees that a dlsym() address converts to a function pointer.
    return reinterpret_cast<Function>(address);
}

EnginePluginBuildInfo read_build_info(plugin_abi::BuildInfoFunction function) {
    EnginePluginBuildInfo info{};
    const EnginePluginBuildInfo* theirs = function();
    if (theirs == nullptr) return info;
    // A plugin of another ABI version may have a shorter struct; read only what it has.
    std::memcpy(&info, theirs, std::min<std::size_t>(theirs->struct_size, sizeof(info)));
    info.engine_version[sizeof(info.engine_version) - 1] = '\0';
    return info;
}

std::string std_library_name(std::int32_t library) {
    switch (library) {
        case plugin_abi::libstdcxx:
            return "libstdc++";
        case plugin_abi::libcxx:
            return "libc++";
        default:
            return "unknown";
    }
}

// Every compiler-ABI fact that differs, as "what: plugin X, engine Y"; empty when all agree.
std::vector<std::string> abi_differences(const EnginePluginBuildInfo& plugin, const EnginePluginBuildInfo& engine) {
    std::vector<std::string> out;
    const auto compare = [&out](const std::string& what, const std::string& theirs, const std::string& ours) {
        if (theirs != ours) out.push_back(what + ": plugin " + theirs + ", engine " + ours);
    };
    compare("C++ standard library", std_library_name(plugin.std_library), std_library_name(engine.std_library));
    compare("libstdc++ dual ABI (_GLIBCXX_USE_CXX11_ABI)", std::to_string(plugin.cxx11_string_abi),
            std::to_string(engine.cxx11_string_abi));
    compare("sizeof(std::string)", std::to_string(plugin.sizeof_std_string), std::to_string(engine.sizeof_std_string));
    compare("_GLIBCXX_DEBUG containers", plugin.debug_containers ? "on" : "off",
            engine.debug_containers ? "on" : "off");
    return out;
}

// " (plugin built against engine X, this is engine Y)" when both releases are known.
std::string built_against(const EnginePluginBuildInfo& plugin, const EnginePluginBuildInfo& engine) {
    const bool has_field = plugin.struct_size >= offsetof(EnginePluginBuildInfo, engine_version) + 1;
    const std::string theirs = has_field ? plugin.engine_version : "";
    const std::string ours = engine.engine_version;
    if (theirs.empty() || theirs == "unknown" || ours == "unknown") return "";
    return " (plugin built against engine " + theirs + ", this is engine " + ours + ")";
}

// Refuses a library whose interface version or compiler ABI differs from the engine's.
void check_abi(void* handle, const std::string& where) {
    const auto version = find_symbol<plugin_abi::AbiVersionFunction>(handle, "engine_plugin_abi_version", where)();
    const auto build_info = find_symbol<plugin_abi::BuildInfoFunction>(handle, "engine_plugin_build_info", where);
    const EnginePluginBuildInfo theirs = read_build_info(build_info);
    constexpr EnginePluginBuildInfo ours = plugin_abi::current_build_info();
    if (version != ours.abi_version)
        fail(where + ": plugin ABI version " + std::to_string(version) + " does not match the engine's " +
             std::to_string(ours.abi_version) + built_against(theirs, ours) + "; rebuild the plugin");
    if (const auto differences = abi_differences(theirs, ours); !differences.empty())
        fail(where + ": plugin compiled with a different C++ ABI (" + join(differences, "; ") +
             "); rebuild it with the engine's compiler settings");
}

LibraryHandle open_library(const std::filesystem::path& library, const std::string& where) {
    std::error_code ignored;
    if (!std::filesystem::is_regular_file(library, ignored)) fail(where + ": no such file");
    dlerror();  // clears a stale error
    LibraryHandle handle(dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL));
    if (handle) return handle;
    const char* reason = dlerror();
    std::string message = where + ": cannot load: " + (reason != nullptr ? reason : "unknown dlopen() error");
    if (message.find("undefined symbol") != std::string::npos)
        message += " (was the plugin built against another engine version or with other compiler settings?)";
    fail(message);
}

}  // namespace

PluginManager::PluginManager(PluginContext context) : context_(context) {}

PluginManager::~PluginManager() {
    shutdown_all();
}

Plugin& PluginManager::add_static(std::unique_ptr<Plugin> plugin) {
    if (plugin == nullptr) fail("engine::PluginManager::add_static(): null plugin");
    auto loaded = std::make_unique<Loaded>();
    loaded->plugin.reset(plugin.release());
    return start(std::move(loaded));
}

Plugin& PluginManager::load_shared(const std::filesystem::path& library) {
    const std::string where = "engine::PluginManager::load_shared(): plugin library '" + library.string() + "'";
    auto loaded = std::make_unique<Loaded>();
    loaded->library = library;
    loaded->handle = open_library(library, where);
    check_abi(loaded->handle.get(), where);
    const auto create = find_symbol<plugin_abi::CreateFunction>(loaded->handle.get(), "engine_plugin_create", where);
    const auto destroy = find_symbol<plugin_abi::DestroyFunction>(loaded->handle.get(), "engine_plugin_destroy", where);
    Plugin* created = nullptr;
    if (const auto error = error_of([&] { created = create(); }); !error.empty())
        fail(where + ": engine_plugin_create() threw: " + error);
    if (created == nullptr) fail(where + ": engine_plugin_create() returned null");
    loaded->plugin = std::unique_ptr<Plugin, PluginDeleter>(created, destroy);
    return start(std::move(loaded));
}

// On any failure `loaded` goes out of scope here, destroying the plugin and closing its library.
Plugin& PluginManager::start(std::unique_ptr<Loaded> loaded) {
    loaded->name = loaded->plugin->name();
    const std::string where = "engine::PluginManager: " + loaded->describe();
    if (const Plugin* existing = find(loaded->name); existing != nullptr)
        fail(where + ": a plugin named '" + loaded->name + "' (version " + existing->version() + ") is already loaded");
    if (const auto error = loaded->startup(context_); !error.empty()) fail(where + ": startup failed: " + error);
    log(LogLevel::debug, "started " + loaded->describe() + " version " + loaded->plugin->version());
    loaded_.push_back(std::move(loaded));
    return *loaded_.back()->plugin;
}

void PluginManager::unload(const std::string& name) {
    const auto it = std::find_if(loaded_.begin(), loaded_.end(), [&](const auto& l) { return l->name == name; });
    if (it == loaded_.end())
        fail("engine::PluginManager::unload(): no plugin named '" + name + "' (loaded: " + join(names()) + ")");
    const std::unique_ptr<Loaded> loaded = std::move(*it);
    loaded_.erase(it);
    if (const auto error = loaded->shutdown(context_); !error.empty())
        fail("engine::PluginManager::unload(): " + loaded->describe() + ": shutdown failed: " + error);
}

// Called from the destructor, so failures are logged rather than thrown; every plugin still
// gets its shutdown and is destroyed.
void PluginManager::shutdown_all() {
    while (!loaded_.empty()) {
        const std::unique_ptr<Loaded> loaded = std::move(loaded_.back());
        loaded_.pop_back();
        if (const auto error = loaded->shutdown(context_); !error.empty())
            log_error("engine::PluginManager: " + loaded->describe() + ": shutdown failed: " + error);
    }
}

std::vector<std::string> PluginManager::names() const {
    std::vector<std::string> out;
    for (const auto& loaded : loaded_) out.push_back(loaded->name);
    return out;
}

Plugin* PluginManager::find(const std::string& name) const {
    for (const auto& loaded : loaded_)
        if (loaded->name == name) return loaded->plugin.get();
    return nullptr;
}

}  // namespace engine
