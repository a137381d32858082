#include "engine/gl/shader_preprocessor.h"

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>

#include "engine/core/error.h"

namespace engine::gl {
namespace {

// Mesa ignores the source-string number of `#line`, so the file index is also encoded in the
// line number itself: line L of file k is reported as k * line_stride + L by every driver.
constexpr long line_stride = 100000;

std::string line_directive(int line, int index) {
    return "#line " + std::to_string(static_cast<long>(index) * line_stride + line) + " " + std::to_string(index) +
           "\n";
}

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return {};
    const auto e = s.find_last_not_of(" \t\r");
    return s.substr(b, e - b + 1);
}

bool starts_with_directive(const std::string& line, const char* directive) {
    const std::string t = trim(line);
    if (t.empty() || t[0] != '#') return false;
    const std::string rest = trim(t.substr(1));
    return rest.rfind(directive, 0) == 0;
}

}  // namespace

ShaderPreprocessor::ShaderPreprocessor(std::filesystem::path root, FileReader reader)
    : roots_{std::move(root)}, reader_(std::move(reader)) {
    if (!reader_) {
        reader_ = [](const std::filesystem::path& path) -> std::optional<std::string> {
            std::ifstream in(path, std::ios::binary);
            if (!in) return std::nullopt;
            std::ostringstream ss;
            ss << in.rdbuf();
            return ss.str();
        };
    }
}

void ShaderPreprocessor::add_root(std::filesystem::path root) {
    if (std::find(roots_.begin(), roots_.end(), root) == roots_.end()) roots_.push_back(std::move(root));
}

std::optional<std::string> ShaderPreprocessor::read(const std::filesystem::path& file) const {
    for (const auto& root : roots_)
        if (auto text = reader_(root / file)) return text;
    return std::nullopt;
}

std::string ShaderPreprocessor::roots_text() const {
    std::string text;
    for (const auto& root : roots_) text += (text.empty() ? "" : ", ") + root.string();
    return text;
}

PreprocessedShader ShaderPreprocessor::process(const std::string& file, const std::vector<std::string>& defines) const {
    PreprocessedShader out;
    out.source = "#version 450 core\n";
    for (const auto& define : defines) {
        const auto eq = define.find('=');
        const std::string name = define.substr(0, eq);
        if (name.empty() || !std::all_of(name.begin(), name.end(), [](char c) {
                return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
            }))
            fail(file + ": invalid shader define '" + define + "'");
        out.source += "#define " + name + (eq == std::string::npos ? "" : " " + define.substr(eq + 1)) + "\n";
    }
    std::vector<std::string> stack;
    expand(std::filesystem::path(file).lexically_normal(), out, stack, "");
    return out;
}

void ShaderPreprocessor::expand(const std::filesystem::path& file, PreprocessedShader& out,
                                std::vector<std::string>& stack, const std::string& included_from) const {
    const std::string name = file.generic_string();
    if (std::find(stack.begin(), stack.end(), name) != stack.end())
        fail(included_from + ": include cycle through '" + name + "'");
    if (std::find(out.files.begin(), out.files.end(), name) != out.files.end()) return;  // once per file
    const auto text = read(file);
    if (!text) {
        if (included_from.empty() && roots_.size() == 1)
            fail((roots_.front() / file).string() + ": shader file not found");
        if (included_from.empty()) fail(name + ": shader file not found in " + roots_text());
        fail(included_from + ": cannot find include '" + name + "' (searched next to the file and in " + roots_text() +
             ")");
    }
    const int index = static_cast<int>(out.files.size());
    out.files.push_back(name);
    stack.push_back(name);

    out.source += line_directive(1, index);
    std::istringstream lines(*text);
    std::string line;
    int number = 0;
    static const std::regex include_re(R"(^\s*#\s*include\s+\"([^\"]+)\"\s*$)");
    while (std::getline(lines, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::string where = name + ":" + std::to_string(number);
        if (starts_with_directive(line, "version")) {
            fail(where + ": '#version' is added by the engine; remove it from the file");
        } else if (starts_with_directive(line, "pragma once")) {
            out.source += "\n";
        } else if (starts_with_directive(line, "include") && line.find('<') != std::string::npos &&
                   line.find('"') == std::string::npos) {
            // `#include <...>` is for C++ only, in the `#ifdef __cplusplus` part of *_shared.h
            // headers; GLSL skips that part, so the line passes through untouched.
            out.source += line + "\n";
        } else if (starts_with_directive(line, "include")) {
            std::smatch match;
            if (!std::regex_match(line, match, include_re))
                fail(where + ": malformed #include (use #include \"file\")");
            std::filesystem::path target = (file.parent_path() / match[1].str()).lexically_normal();
            if (!read(target)) target = std::filesystem::path(match[1].str()).lexically_normal();
            expand(target, out, stack, where);
            out.source += line_directive(number + 1, index);
        } else {
            out.source += line + "\n";
        }
    }
    stack.pop_back();
}

std::string map_shader_log(const std::string& log, const std::vector<std::string>& files) {
    // Mesa: "0:12(5): error: ..."; NVIDIA: "0(12) : error C0000: ...".
    static const std::regex mesa_re(R"((\d+):(\d+)\((\d+)\))");
    static const std::regex nvidia_re(R"(^(\d+)\((\d+)\))");
    std::istringstream in(log);
    std::string line, result;
    while (std::getline(in, line)) {
        std::smatch m;
        // Prefer the index encoded in the line number; fall back to the source-string number.
        auto location = [&](const std::string& source, const std::string& line_text) {
            const long reported = std::stol(line_text);
            std::size_t index = static_cast<std::size_t>(std::stoul(source));
            if (reported >= line_stride) index = static_cast<std::size_t>(reported / line_stride);
            const std::string name = index < files.size() ? files[index] : "source " + std::to_string(index);
            return name + ":" + std::to_string(reported % line_stride);
        };
        if (std::regex_search(line, m, mesa_re) && m.position(0) == 0) {
            line = location(m[1], m[2]) + ":" + m[3].str() + m.suffix().str();
        } else if (std::regex_search(line, m, nvidia_re)) {
            line = location(m[1], m[2]) + m.suffix().str();
        }
        result += line + "\n";
    }
    return result;
}

}  // namespace engine::gl
