#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/platform/gl_context.h"

TEST(GlContext, HeadlessContextHasComputeShaders) {
    auto context = engine::HeadlessGlContext::create();
    const auto& info = context->info();
    EXPECT_TRUE(info.major > 4 || (info.major == 4 && info.minor >= 3)) << info.version;
    EXPECT_FALSE(info.renderer.empty());
}

TEST(GlContext, MissingComputeIsAClearError) {
    engine::GlInfo info{"SomeVendor", "OldCard", "3.3 Core", "surfaceless", 3, 3};
    try {
        engine::require_compute_support(info);
        FAIL() << "expected an error";
    } catch (const engine::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("4.3"), std::string::npos) << what;
        EXPECT_NE(what.find("OldCard"), std::string::npos) << what;
        EXPECT_NE(what.find("3.3 Core"), std::string::npos) << what;
    }
}
