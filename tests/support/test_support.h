#pragma once
// Helpers shared by the test tiers: data locations, a process-wide headless GL context for the
// gpu tier, and golden-image comparison that writes the actual and difference images on failure.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace engine::test {

std::filesystem::path source_dir();          // tests/
std::filesystem::path repo_dir();            // the repository root
std::filesystem::path shared_data_dir();     // ../shared/data (may be absent on a user's clone)
// build/test_output/<suite>/<TestSuite.TestName>/ (created): each test writes only its own folder.
std::filesystem::path output_dir(const std::string& suite);

// Skips the calling test with a clear message when ../shared/data is absent.
#define ENGINE_REQUIRE_SHARED_DATA()                                                            \
    do {                                                                                        \
        if (!std::filesystem::exists(::engine::test::shared_data_dir()))                        \
            GTEST_SKIP() << "shared data folder not found at " << ::engine::test::shared_data_dir(); \
    } while (0)

}  // namespace engine::test
