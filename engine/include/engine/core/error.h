#pragma once
// The engine reports every failure it can describe as engine::Error, whose message names what
// failed and where (file, key, byte offset). Callers at a program's edge print what() and exit.
#include <stdexcept>
#include <string>

namespace engine {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws engine::Error with the message; a single place to break on in a debugger.
[[noreturn]] void fail(const std::string& message);

}  // namespace engine
