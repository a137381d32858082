#pragma once
// Compiles and caches programs from files under shaders/. The stage comes from the file name
// (`*.vert.glsl`, `*.frag.glsl`, `*.comp.glsl`); variants come from `#define`s. Compile and link
// errors throw engine::Error with `file:line` locations.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/gl/objects.h"
#include "engine/gl/shader_preprocessor.h"

namespace engine::gl {

// ENGINE_SHADER_DIR from the environment, else the source tree's shaders/ folder.
std::filesystem::path default_shader_dir();

class ShaderLibrary {
public:
    explicit ShaderLibrary(std::filesystem::path root = default_shader_dir());

    // The program made of `files` (one per stage) with `defines`; compiled on first use.
    const Program& program(const std::vector<std::string>& files, const std::vector<std::string>& defines = {});

    // Another folder of shader files, searched after the ones before it (a plugin's own shaders).
    void add_root(std::filesystem::path root) { preprocessor_.add_root(std::move(root)); }

    const ShaderPreprocessor& preprocessor() const { return preprocessor_; }
    std::size_t cached_programs() const { return programs_.size(); }

private:
    Program build(const std::vector<std::string>& files, const std::vector<std::string>& defines) const;

    ShaderPreprocessor preprocessor_;
    std::map<std::string, Program> programs_;
};

// The stage of a shader file from its name, or throws naming the file.
GLenum shader_stage_from_name(const std::string& file);

}  // namespace engine::gl
