#pragma once
// The binary contract between the engine and a plugin loaded at run time with
// PluginManager::load_shared(). A shared plugin exports four C functions, all defined by
// ENGINE_EXPORT_PLUGIN(ClassName) in one of its .cpp files:
//
//   engine_plugin_abi_version()  the plugin interface version it was compiled against
//   engine_plugin_build_info()   the compiler ABI facts that must agree with the engine's
//   engine_plugin_create()       a new plugin object, owned by the engine until ...
//   engine_plugin_destroy()      ... it hands it back, so the library's own delete frees it
//
// Plugin objects cross the boundary as C++ classes (virtual calls, std::string returns), so the
// interface version alone is not enough: a plugin compiled with another standard library or the
// other libstdc++ std::string ABI would crash instead of failing. The build info lets the engine
// refuse it and say exactly what differs.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/plugin/plugin.h"

// Raised whenever Plugin, PluginContext or an engine type that plugins use changes in a way that
// breaks compiled plugins. Overridable only so that tests can build a deliberately stale plugin.
#ifndef ENGINE_PLUGIN_ABI_VERSION
#define ENGINE_PLUGIN_ABI_VERSION 2  // 2: Plugin::add_ui_panels
#endif

// The engine release, shown in mismatch messages; CMake should pass PROJECT_VERSION.
#ifndef ENGINE_VERSION_STRING
#define ENGINE_VERSION_STRING "unknown"
#endif

#define ENGINE_PLUGIN_EXPORT __attribute__((visibility("default")))

extern "C" {

// Plain C data so that any engine can read any plugin's copy. `struct_size` and `abi_version`
// stay first forever; the engine reads only the fields that `struct_size` covers.
struct EnginePluginBuildInfo {
    std::uint32_t struct_size;
    std::int32_t abi_version;       // ENGINE_PLUGIN_ABI_VERSION
    std::int32_t std_library;       // engine::plugin_abi::StdLibrary
    std::int32_t cxx11_string_abi;  // _GLIBCXX_USE_CXX11_ABI (1 new, 0 old), −1 outside libstdc++
    std::int32_t debug_containers;  // 1 under _GLIBCXX_DEBUG, whose containers differ in layout
    std::uint32_t sizeof_std_string;
    std::int32_t itanium_abi;  // __GXX_ABI_VERSION; informational, GCC and Clang differ yet agree
    char engine_version[24];   // ENGINE_VERSION_STRING, NUL-terminated, informational
};

ENGINE_PLUGIN_EXPORT int engine_plugin_abi_version();
ENGINE_PLUGIN_EXPORT const EnginePluginBuildInfo* engine_plugin_build_info();
ENGINE_PLUGIN_EXPORT engine::Plugin* engine_plugin_create();
ENGINE_PLUGIN_EXPORT void engine_plugin_destroy(engine::Plugin* plugin);

}  // extern "C"

namespace engine::plugin_abi {

enum StdLibrary : std::int32_t { other = 0, libstdcxx = 1, libcxx = 2 };

// The facts of the translation unit that includes this header: a plugin's when expanded by
// ENGINE_EXPORT_PLUGIN, the engine's when called from plugin_manager.cpp.
constexpr EnginePluginBuildInfo current_build_info() {
    EnginePluginBuildInfo info{};
    info.struct_size = sizeof(EnginePluginBuildInfo);
    info.abi_version = ENGINE_PLUGIN_ABI_VERSION;
#if defined(_LIBCPP_VERSION)
    info.std_library = libcxx;
#elif defined(__GLIBCXX__)
    info.std_library = libstdcxx;
#else
    info.std_library = other;
#endif
#if defined(_GLIBCXX_USE_CXX11_ABI)
    info.cxx11_string_abi = _GLIBCXX_USE_CXX11_ABI;
#else
    info.cxx11_string_abi = -1;
#endif
#if defined(_GLIBCXX_DEBUG)
    info.debug_containers = 1;
#endif
    info.sizeof_std_string = sizeof(std::string);
#if defined(__GXX_ABI_VERSION)
    info.itanium_abi = __GXX_ABI_VERSION;
#endif
    constexpr char version[] = ENGINE_VERSION_STRING;
    static_assert(sizeof(version) <= sizeof(info.engine_version), "ENGINE_VERSION_STRING is too long");
    for (std::size_t i = 0; i < sizeof(version); ++i) info.engine_version[i] = version[i];
    return info;
}

// Signatures of the exported functions, for dlsym().
using AbiVersionFunction = int (*)();
using BuildInfoFunction = const EnginePluginBuildInfo* (*)();
using CreateFunction = Plugin* (*)();
using DestroyFunction = void (*)(Plugin*);

}  // namespace engine::plugin_abi

// Defines the four entry points for a plugin class with a default constructor. Use it once, in
// a plugin built with engine_add_plugin(<name> SHARED ...), outside any namespace.
#define ENGINE_EXPORT_PLUGIN(ClassName)                                                           \
    extern "C" ENGINE_PLUGIN_EXPORT int engine_plugin_abi_version() {                             \
        return ENGINE_PLUGIN_ABI_VERSION;                                                         \
    }                                                                                             \
    extern "C" ENGINE_PLUGIN_EXPORT const EnginePluginBuildInfo* engine_plugin_build_info() {     \
        static constexpr EnginePluginBuildInfo info = ::engine::plugin_abi::current_build_info(); \
        return &info;                                                                             \
    }                                                                                             \
    extern "C" ENGINE_PLUGIN_EXPORT ::engine::Plugin* engine_plugin_create() {                    \
        return new ClassName();                                                                   \
    }                                                                                             \
    extern "C" ENGINE_PLUGIN_EXPORT void engine_plugin_destroy(::engine::Plugin* plugin) {        \
        delete plugin;                                                                            \
    }
