// Replays inputs through a harness's LLVMFuzzerTestOneInput without libFuzzer, so the normal
// (GCC) and sanitizer builds run every committed regression input and seed as a ctest test:
//   fuzz_replay_<name> FILE_OR_FOLDER...
// Folders are read one level deep in name order; README.md files and arguments starting with '-'
// (libFuzzer options) are skipped. A crash or a broken promise aborts; otherwise exit 0, or 1 when
// no input was found (a wrong path should not pass as a clean run).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> inputs_of(const std::vector<std::string>& arguments) {
    std::vector<fs::path> inputs;
    for (const auto& argument : arguments) {
        if (argument.empty() || argument[0] == '-') continue;
        if (!fs::is_directory(argument)) {
            inputs.emplace_back(argument);
            continue;
        }
        std::vector<fs::path> files;
        for (const auto& entry : fs::directory_iterator(argument))
            if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
        std::sort(files.begin(), files.end());
        inputs.insert(inputs.end(), files.begin(), files.end());
    }
    return inputs;
}

}  // namespace

int main(int argc, char** argv) {
    const auto inputs = inputs_of(std::vector<std::string>(argv + 1, argv + argc));
    for (const auto& input : inputs) {
        std::ifstream in(input, std::ios::binary);
        if (!in) {
            std::fprintf(stderr, "replay: cannot read %s\n", input.c_str());
            return 1;
        }
        const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::printf("replay: %s (%zu bytes)\n", input.c_str(), bytes.size());
        std::fflush(stdout);
        // A heap block of exactly the input's size, as libFuzzer passes it, so that a read past
        // the end is an overflow the sanitizers see.
        const auto exact = std::make_unique<std::uint8_t[]>(bytes.size());
        std::copy(bytes.begin(), bytes.end(), exact.get());
        LLVMFuzzerTestOneInput(exact.get(), bytes.size());
    }
    if (inputs.empty()) {
        std::fprintf(stderr, "replay: no inputs found\n");
        return 1;
    }
    std::printf("replay: %zu inputs, no crash\n", inputs.size());
    return 0;
}
