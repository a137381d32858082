#pragma once
// Turns a GLSL file from shaders/ into one compilable source: a `#version 450 core` line, a
// `#define` preamble for the variant, `#include "..."` resolved (relative to the including file,
// then to the shader root; each file at most once), and `#line` directives so that compiler
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
    // Reads a file relative to the root; returns nullopt when it does not exist.
    using FileReader = std::function<std::optional<std::string>(const std::filesystem::path&)>;

    explicit ShaderPreprocessor(std::filesystem::path root, FileReader reader = {});

    // `defines` are "NAME" or "NAME=VALUE". Errors (missing file or include, include cycle,
    // malformed directive) throw engine::Error as "file:line: message".
    PreprocessedShader process(const std::string& file, const std::vector<std::string>& defines = {}) const;

    const std::filesystem::path& root() const { return root_; }

private:
    void expand(const std::filesystem::path& file, PreprocessedShader& out, std::vector<std::string>& stack,
                const std::string& included_from) const;
    std::optional<std::string> read(const std::filesystem::path& file) const;

    std::filesystem::path root_;
    FileReader reader_;
};

// Rewrites a GL compiler log so that "<index>:<line>(<col>)" (Mesa) and "<index>(<line>)"
// (NVIDIA) locations read "file:line".
std::string map_shader_log(const std::string& log, const std::vector<std::string>& files);

}  // namespace engine::gl
