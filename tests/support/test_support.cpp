#include "test_support.h"

#include <cstdlib>

namespace engine::test {
namespace {

// $name when it is set and not empty, else the compiled-in folder.
std::filesystem::path folder_from(const char* name, const char* compiled_in) {
    const char* overridden = std::getenv(name);
    auto folder = std::filesystem::path(overridden != nullptr && *overridden != '\0' ? overridden : compiled_in)
                      .lexically_normal();
    // "x/tests/" names the folder "x/tests" (its parent is "x").
    if (folder.has_parent_path() && !folder.has_filename()) folder = folder.parent_path();
    return folder;
}

}  // namespace

std::filesystem::path source_dir() {
    return folder_from("ENGINE_TEST_SOURCE_DIR", TEST_SOURCE_DIR);
}
std::filesystem::path output_root() {
    return folder_from("ENGINE_TEST_OUTPUT_DIR", TEST_OUTPUT_DIR);
}
std::filesystem::path repo_dir() {
    return source_dir().parent_path();
}
std::filesystem::path shared_data_dir() {
    return folder_from("ENGINE_SHARED_DATA_DIR", TEST_SHARED_DATA_DIR);
}
std::filesystem::path data_file(const std::string& relative) {
    auto in_repository = source_dir() / "data" / relative;
    if (std::filesystem::exists(in_repository)) return in_repository;
    return shared_data_dir() / relative;
}
std::filesystem::path output_dir(const std::string& suite) {
    // One folder per test: ctest runs tests in parallel, each as its own process.
    auto dir = output_root() / suite;
    if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info())
        dir /= std::string(info->test_suite_name()) + "." + info->name();
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace engine::test
