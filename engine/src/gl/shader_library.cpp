#include "engine/gl/shader_library.h"

#include <cstdlib>

#include "engine/core/error.h"

namespace engine::gl {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string info_log(GLuint object, bool is_program) {
    GLint length = 0;
    if (is_program)
        glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
    else
        glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    if (is_program)
        glGetProgramInfoLog(object, length, nullptr, log.data());
    else
        glGetShaderInfoLog(object, length, nullptr, log.data());
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log;
}

std::string join(const std::vector<std::string>& items, const char* separator) {
    std::string out;
    for (const auto& item : items) out += (out.empty() ? "" : separator) + item;
    return out;
}

}  // namespace

std::filesystem::path default_shader_dir() {
    if (const char* env = std::getenv("ENGINE_SHADER_DIR"); env != nullptr && env[0] != '\0') return env;
    return ENGINE_DEFAULT_SHADER_DIR;
}

GLenum shader_stage_from_name(const std::string& file) {
    if (ends_with(file, ".vert.glsl")) return GL_VERTEX_SHADER;
    if (ends_with(file, ".frag.glsl")) return GL_FRAGMENT_SHADER;
    if (ends_with(file, ".comp.glsl")) return GL_COMPUTE_SHADER;
    if (ends_with(file, ".geom.glsl")) return GL_GEOMETRY_SHADER;
    fail(file + ": cannot tell the shader stage (name it *.vert.glsl, *.frag.glsl or *.comp.glsl)");
}

ShaderLibrary::ShaderLibrary(std::filesystem::path root) : preprocessor_(std::move(root)) {}

const Program& ShaderLibrary::program(const std::vector<std::string>& files, const std::vector<std::string>& defines) {
    const std::string key = join(files, "+") + "|" + join(defines, ";");
    auto it = programs_.find(key);
    if (it == programs_.end()) it = programs_.emplace(key, build(files, defines)).first;
    return it->second;
}

Program ShaderLibrary::build(const std::vector<std::string>& files, const std::vector<std::string>& defines) const {
    Program program(join(files, "+"));
    std::vector<GLuint> shaders;
    auto cleanup = [&] {
        for (GLuint s : shaders) glDeleteShader(s);
    };
    for (const auto& file : files) {
        const GLenum stage = shader_stage_from_name(file);
        const PreprocessedShader pre = preprocessor_.process(file, defines);
        const GLuint shader = glCreateShader(stage);
        shaders.push_back(shader);
        const char* text = pre.source.c_str();
        glShaderSource(shader, 1, &text, nullptr);
        glCompileShader(shader);
        GLint ok = GL_FALSE;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (ok != GL_TRUE) {
            const std::string log = map_shader_log(info_log(shader, false), pre.files);
            cleanup();
            fail("shader compile failed: " + file + (defines.empty() ? "" : " [" + join(defines, ", ") + "]") + "\n" +
                 log);
        }
        glAttachShader(program.id(), shader);
    }
    glLinkProgram(program.id());
    GLint ok = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    cleanup();
    if (ok != GL_TRUE) fail("shader link failed: " + join(files, " + ") + "\n" + info_log(program.id(), true));
    return program;
}

}  // namespace engine::gl
