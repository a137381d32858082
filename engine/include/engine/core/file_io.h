#pragma once
// Whole-file reads and crash-safe writes. Errors name the file and the reason.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace engine {

std::vector<std::uint8_t> read_binary_file(const std::filesystem::path& path);
std::string read_text_file(const std::filesystem::path& path);

// Writes to "<path>.tmp-<pid>" and renames over `path`, so a failure or a kill leaves any
// previous file intact.
void write_file_atomic(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void write_text_file_atomic(const std::filesystem::path& path, const std::string& text);

}  // namespace engine
