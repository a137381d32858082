#pragma once
// Helpers shared by the test tiers: data locations, a process-wide headless GL context for the
// gpu tier, and golden-image comparison that writes the actual and difference images on failure.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace engine::test {

// The folders below are compiled in (the build's source and build trees); each can be moved with an
// environment variable when set and not empty, as a packed copy of the tests does (scripts/gpu-check):
// ENGINE_TEST_SOURCE_DIR for tests/ (the repository root is its parent), ENGINE_TEST_OUTPUT_DIR for
// build/test_output, ENGINE_SHARED_DATA_DIR for ../shared/data.
std::filesystem::path source_dir();  // tests/
std::filesystem::path repo_dir();    // the repository root
// build/test_output/ (not created): the root of every test's output.
std::filesystem::path output_root();
// ../shared/data (may be absent on a user's clone), or $ENGINE_SHARED_DATA_DIR when that is set and
// not empty (ENGINE_SHARED_DATA_DIR=/nonexistent runs the tests as on a clone without it).
std::filesystem::path shared_data_dir();
// A real test asset by its path relative to the data folders: tests/data/<relative> (the small
// captures kept in the repository) when it is there, else shared_data_dir()/<relative>.
std::filesystem::path data_file(const std::string& relative);
// build/test_output/<suite>/<TestSuite.TestName>/ (created): each test writes only its own folder.
std::filesystem::path output_dir(const std::string& suite);

// Skips the calling test with a clear message when ../shared/data is absent.
#define ENGINE_REQUIRE_SHARED_DATA()                                                                 \
    do {                                                                                             \
        if (!std::filesystem::exists(::engine::test::shared_data_dir()))                             \
            GTEST_SKIP() << "shared data folder not found at " << ::engine::test::shared_data_dir(); \
    } while (0)

// Skips the calling test, naming the file, when `relative` is neither in tests/data nor in the
// shared data folder (see data_file).
#define ENGINE_REQUIRE_DATA(relative)                                             \
    do {                                                                          \
        if (!std::filesystem::exists(::engine::test::data_file(relative)))        \
            GTEST_SKIP() << "test data file " << (relative) << " not found in "   \
                         << (::engine::test::source_dir() / "data") << " nor in " \
                         << ::engine::test::shared_data_dir();                    \
    } while (0)

}  // namespace engine::test
