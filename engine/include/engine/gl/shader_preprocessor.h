#pragma once
// Turns a GLSL file from shaders/ into one compilable source: a `#version 450 core` line, a
// `#define` preamble for the variant, `#include "..."` resolved (relative to the including file,
// then to each shader root in order; each file at most once), and `#line` directives so that compiler
// messages map back to `file:line`. Because Mesa ignores the source-string number of `#line`,
// line L of file k is numbered k·100000 + L (and k is also given as the source-string number);
// map_shader_log() decodes both. Needs no GL, so tests run it alone.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace engine::gl {

struct PreprocessedShader {
    std::string source;
    std::vector<std::string> files;  // index = the source-string number used in #line
};

class ShaderPreprocessor {
public:
    // Reads a file (a full path: a root joined with a name); returns nullopt when it does not exist.
    using FileReader = std::function<std::optional<std::string>(const std::filesystem::path&)>;

    explicit ShaderPreprocessor(std::filesystem::path root, FileReader reader = {});

    // `defines` are "NAME" or "NAME=VALUE". Errors (missing file or include, include cycle,
    // malformed directive) throw engine::Error as "file:line: message".
    PreprocessedShader process(const std::string& file, const std::vector<std::string>& defines = {}) const;

    // Another folder to look in after those given before (plugins add their own shader folders).
    void add_root(std::filesystem::path root);
    const std::filesystem::path& root() const { return roots_.front(); }
    const std::vector<std::filesystem::path>& roots() const { return roots_; }

private:
    void expand(const std::filesystem::path& file, PreprocessedShader& out, std::vector<std::string>& stack,
                const std::string& included_from) const;
    std::optional<std::string> read(const std::filesystem::path& file) const;

    std::string roots_text() const;  // "a, b" for error messages

    std::vector<std::filesystem::path> roots_;
    FileReader reader_;
};

// Rewrites a GL compiler log so that "<index>:<line>(<col>)" (Mesa) and "<index>(<line>)"
// (NVIDIA) locations read "file:line".
std::string map_shader_log(const std::string& log, const std::vector<std::string>& files);

}  // namespace engine::gl
