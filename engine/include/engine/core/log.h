#pragma once
#include <string_view>

namespace engine {

enum class LogLevel { debug, info, warning, error };

void log(LogLevel level, std::string_view message);
inline void log_info(std::string_view m) {
    log(LogLevel::info, m);
}
inline void log_warning(std::string_view m) {
    log(LogLevel::warning, m);
}
inline void log_error(std::string_view m) {
    log(LogLevel::error, m);
}

// Messages below this level are dropped (default: info; ENGINE_LOG=debug|info|warning|error).
void set_log_level(LogLevel level);
LogLevel log_level();

}  // namespace engine
