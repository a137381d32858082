#include "engine/core/file_io.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>
#include <unistd.h>

#include "engine/core/error.h"

namespace engine {
namespace {

std::string reason() { return std::strerror(errno); }

}  // namespace

std::vector<std::uint8_t> read_binary_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) fail(path.string() + ": is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path.string() + ": cannot open: " + reason());
    in.seekg(0, std::ios::end);
    const auto size = static_cast<std::size_t>(in.tellg());
    in.seekg(0, std::ios::beg);
    std::vector<std::uint8_t> bytes(size);
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
        fail(path.string() + ": read failed: " + reason());
    return bytes;
}

std::string read_text_file(const std::filesystem::path& path) {
    const auto bytes = read_binary_file(path);
    return std::string(bytes.begin(), bytes.end());
}

void write_file_atomic(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
    if (path.has_parent_path()) {
        std::error_code ec;
        std::filesystem::create_directories(path.parent_path(), ec);
        if (ec) fail(path.string() + ": cannot create folder: " + ec.message());
    }
    auto temp = path;
    temp += ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) fail(temp.string() + ": cannot create: " + reason());
        out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
        out.flush();
        if (!out) {
            const auto why = reason();
            std::filesystem::remove(temp);
            fail(temp.string() + ": write failed: " + why);
        }
    }
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        std::filesystem::remove(temp);
        fail(path.string() + ": cannot replace: " + ec.message());
    }
}

void write_text_file_atomic(const std::filesystem::path& path, const std::string& text) {
    write_file_atomic(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace engine
