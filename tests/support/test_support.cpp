#include "test_support.h"

namespace engine::test {

std::filesystem::path source_dir() { return TEST_SOURCE_DIR; }
std::filesystem::path repo_dir() { return source_dir().parent_path(); }
std::filesystem::path shared_data_dir() {
    return std::filesystem::path(TEST_SHARED_DATA_DIR).lexically_normal();
}
std::filesystem::path output_dir(const std::string& suite) {
    // One folder per test: ctest runs tests in parallel, each as its own process.
    auto dir = std::filesystem::path(TEST_OUTPUT_DIR) / suite;
    if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info())
        dir /= std::string(info->test_suite_name()) + "." + info->name();
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace engine::test
