#include "engine/core/log.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace engine {
namespace {

LogLevel level_from_environment() {
    const char* value = std::getenv("ENGINE_LOG");
    if (value == nullptr) return LogLevel::info;
    if (std::strcmp(value, "debug") == 0) return LogLevel::debug;
    if (std::strcmp(value, "warning") == 0) return LogLevel::warning;
    if (std::strcmp(value, "error") == 0) return LogLevel::error;
    return LogLevel::info;
}

std::atomic<LogLevel>& current_level() {
    static std::atomic<LogLevel> level{level_from_environment()};
    return level;
}

const char* prefix(LogLevel level) {
    switch (level) {
        case LogLevel::debug:
            return "debug";
        case LogLevel::info:
            return "info";
        case LogLevel::warning:
            return "warning";
        case LogLevel::error:
            return "error";
    }
    return "?";
}

}  // namespace

void set_log_level(LogLevel level) {
    current_level() = level;
}
LogLevel log_level() {
    return current_level();
}

void log(LogLevel level, std::string_view message) {
    if (level < current_level().load()) return;
    static std::mutex mutex;
    std::lock_guard lock(mutex);
    std::fprintf(stderr, "[%s] %.*s\n", prefix(level), static_cast<int>(message.size()), message.data());
}

}  // namespace engine
