#include "test_support.h"

#include <cstdlib>

namespace engine::test {

std::filesystem::path source_dir() {
    return TEST_SOURCE_DIR;
}
std::filesystem::path repo_dir() {
    return source_dir().parent_path();
}
std::filesystem::path shared_data_dir() {
    const char* overridden = std::getenv("ENGINE_SHARED_DATA_DIR");
    const char* dir = overridden != nullptr && *overridden != '\0' ? overridden : TEST_SHARED_DATA_DIR;
    return std::filesystem::path(dir).lexically_normal();
}
std::filesystem::path data_file(const std::string& relative) {
    auto in_repository = source_dir() / "data" / relative;
    if (std::filesystem::exists(in_repository)) return in_repository;
    return shared_data_dir() / relative;
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
