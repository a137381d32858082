#include <map>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/gl/shader_preprocessor.h"

using engine::gl::ShaderPreprocessor;

namespace {

ShaderPreprocessor make(std::map<std::string, std::string> files) {
    return ShaderPreprocessor("/virtual", [files](const std::filesystem::path& p) -> std::optional<std::string> {
        const auto key = p.lexically_relative("/virtual").generic_string();
        const auto it = files.find(key);
        if (it == files.end()) return std::nullopt;
        return it->second;
    });
}

std::string error_of(const ShaderPreprocessor& pre, const std::string& file) {
    try {
        pre.process(file);
    } catch (const engine::Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(ShaderPreprocessor, AddsVersionDefinesAndLineDirectives) {
    const auto pre = make({{"a/main.comp.glsl", "void main() {}\n"}});
    const auto out = pre.process("a/main.comp.glsl", {"FOO", "BAR=3"});
    EXPECT_EQ(out.source.rfind("#version 450 core\n#define FOO\n#define BAR 3\n#line 1 0\n", 0), 0u) << out.source;
    ASSERT_EQ(out.files.size(), 1u);
    EXPECT_EQ(out.files[0], "a/main.comp.glsl");
}

TEST(ShaderPreprocessor, SearchesTheRootsInOrderForFilesAndIncludes) {
    // Two roots, as when a plugin adds its shaders folder to the engine's: a plugin file includes the
    // engine's common code, and a name in both roots comes from the first.
    const std::map<std::string, std::string> files = {
        {"/engine/common/math.glsl", "float sq(float x) { return x * x; }\n"},
        {"/engine/p/shadowed.glsl", "// engine\n"},
        {"/plugin/p/main.comp.glsl", "#include \"common/math.glsl\"\n#include \"shadowed.glsl\"\nvoid main() {}\n"},
        {"/plugin/p/shadowed.glsl", "// plugin\n"},
    };
    ShaderPreprocessor pre("/engine", [files](const std::filesystem::path& p) -> std::optional<std::string> {
        const auto it = files.find(p.generic_string());
        if (it == files.end()) return std::nullopt;
        return it->second;
    });
    EXPECT_NE(error_of(pre, "p/main.comp.glsl").find("shader file not found"), std::string::npos);
    pre.add_root("/plugin");
    pre.add_root("/plugin");  // once
    ASSERT_EQ(pre.roots().size(), 2u);
    const auto out = pre.process("p/main.comp.glsl");
    ASSERT_EQ(out.files.size(), 3u);
    EXPECT_EQ(out.files[1], "common/math.glsl");
    EXPECT_NE(out.source.find("// engine"), std::string::npos) << "p/shadowed.glsl is the first root's";
    EXPECT_EQ(out.source.find("// plugin"), std::string::npos);
    EXPECT_NE(error_of(pre, "p/missing.comp.glsl").find("not found in /engine, /plugin"), std::string::npos);
}

TEST(ShaderPreprocessor, ResolvesIncludesRelativeThenFromRootOncePerFile) {
    const auto pre = make({
        {"a/main.comp.glsl",
         "#include \"near.glsl\"\n#include \"common/math.glsl\"\n#include \"near.glsl\"\nvoid main() {}\n"},
        {"a/near.glsl", "// near\n#include \"../common/math.glsl\"\n"},
        {"common/math.glsl", "#pragma once\nfloat sq(float x) { return x * x; }\n"},
    });
    const auto out = pre.process("a/main.comp.glsl");
    ASSERT_EQ(out.files.size(), 3u);
    EXPECT_EQ(out.files[1], "a/near.glsl");
    EXPECT_EQ(out.files[2], "common/math.glsl");
    // math.glsl appears once even though it is included twice.
    EXPECT_EQ(out.source.find("float sq"), out.source.rfind("float sq"));
    // After the include of near.glsl the main file resumes at its line 2; included files'
    // lines carry their index (k * 100000 + line).
    EXPECT_NE(out.source.find("#line 2 0\n"), std::string::npos) << out.source;
    EXPECT_NE(out.source.find("#line 100001 1\n"), std::string::npos) << out.source;
    EXPECT_NE(out.source.find("#line 200001 2\n"), std::string::npos) << out.source;
}

TEST(ShaderPreprocessor, ReportsMissingIncludeWithFileAndLine) {
    const auto pre = make({{"m.comp.glsl", "void f();\n#include \"gone.glsl\"\n"}});
    const std::string e = error_of(pre, "m.comp.glsl");
    EXPECT_NE(e.find("m.comp.glsl:2"), std::string::npos) << e;
    EXPECT_NE(e.find("gone.glsl"), std::string::npos) << e;
}

TEST(ShaderPreprocessor, ReportsIncludeCycle) {
    const auto pre = make({{"a.glsl", "#include \"b.glsl\"\n"}, {"b.glsl", "#include \"a.glsl\"\n"}});
    const std::string e = error_of(pre, "a.glsl");
    EXPECT_NE(e.find("include cycle"), std::string::npos) << e;
    EXPECT_NE(e.find("b.glsl:1"), std::string::npos) << e;
}

TEST(ShaderPreprocessor, RejectsVersionLineAndBadDefine) {
    const auto pre = make({{"v.comp.glsl", "#version 430\n"}, {"ok.comp.glsl", "\n"}});
    EXPECT_NE(error_of(pre, "v.comp.glsl").find("v.comp.glsl:1"), std::string::npos);
    EXPECT_THROW(pre.process("ok.comp.glsl", {"BAD NAME"}), engine::Error);
    EXPECT_NE(error_of(pre, "missing.comp.glsl").find("not found"), std::string::npos);
}

TEST(ShaderPreprocessor, MapsMesaAndNvidiaLogsToFileLine) {
    const std::vector<std::string> files{"main.comp.glsl", "common/math.glsl"};
    EXPECT_EQ(engine::gl::map_shader_log("1:12(5): error: `x' undeclared", files),
              "common/math.glsl:12:5: error: `x' undeclared\n");
    EXPECT_EQ(engine::gl::map_shader_log("0(7) : error C1008: undefined variable", files),
              "main.comp.glsl:7 : error C1008: undefined variable\n");
    // Mesa drops the source-string number: the index comes from the encoded line.
    EXPECT_EQ(engine::gl::map_shader_log("0:100012(5): error: x", files), "common/math.glsl:12:5: error: x\n");
    EXPECT_EQ(engine::gl::map_shader_log("1(100003) : error C0000: y", files), "common/math.glsl:3 : error C0000: y\n");
}
