#include "test_support.h"

namespace engine::test {

std::filesystem::path source_dir() { return TEST_SOURCE_DIR; }
std::filesystem::path repo_dir() { return source_dir().parent_path(); }
std::filesystem::path shared_data_dir() {
    return std::filesystem::path(TEST_SHARED_DATA_DIR).lexically_normal();
}
std::filesystem::path output_dir(const std::string& suite) {
    auto dir = std::filesystem::path(TEST_OUTPUT_DIR) / suite;
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace engine::test
