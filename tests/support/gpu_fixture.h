#pragma once
// The gpu test tier: one headless GL context per test binary, and golden-image comparison.
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "engine/platform/gl_context.h"
#include "engine/render/image.h"

namespace engine::test {

// Creates the context on first use and keeps it for the whole test binary.
HeadlessGlContext& gl_context();

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override { gl_context().make_current(); }
};

struct GoldenTolerance {
    double min_psnr_db = 35.0;   // whole-image PSNR against the golden
    int channel_threshold = 24;  // a pixel "differs" when a channel is off by more
    double max_fraction_differing = 0.005;
};

// Compares `actual` with tests/golden/<name>.png. On failure writes <name>.actual.png and
// <name>.diff.png to build/test_output/golden/ and says where. With ENGINE_UPDATE_GOLDEN=1 it
// (re)writes the golden instead and passes.
::testing::AssertionResult matches_golden(const Image& actual, const std::string& name,
                                          const GoldenTolerance& tolerance = {});

}  // namespace engine::test
