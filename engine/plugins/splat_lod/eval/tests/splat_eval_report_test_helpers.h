#pragma once
// Shared by the splat_eval_report_test* files: checking an engine::Error's message and reading a
// written report back.
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"

namespace splat_eval_report_test {

// Fails the calling test unless `f` throws an engine::Error whose message holds every one of `parts`.
template <class F>
void expect_error(F&& f, std::initializer_list<std::string> parts) {
    try {
        f();
        ADD_FAILURE() << "no engine::Error thrown";
    } catch (const engine::Error& e) {
        for (const auto& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

// The whole text of the file at `path` ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace splat_eval_report_test
