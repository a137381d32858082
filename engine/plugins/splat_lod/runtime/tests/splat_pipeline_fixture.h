#pragma once
// The fixture of the GPU splat pipeline's tests (splat_pipeline_test.cpp, splat_transitions_test.cpp):
// a splat render harness and the double-precision CPU reference render to compare it with.
#include <memory>
#include <span>

#include "gpu_fixture.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_cloud.h"
#include "splat_test_scenes.h"

class SplatPipelineTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness harness;

    engine::Image reference(const splat_lod::SplatCloud& cloud, const engine::CameraView& camera,
                            const glm::vec3& background = glm::vec3(0.0f)) {
        const splat_lod::reference::ReferenceInstance instance{&cloud, glm::dmat4(1.0), splat_lod::kMaxShDegree};
        splat_lod::reference::ReferenceSettings settings;
        settings.background = glm::dvec3(background);
        return splat_lod::reference::to_image8(
            splat_lod::reference::render_reference(std::span(&instance, 1), camera, settings));
    }

    void expect_no_garbage(const engine::Image& image) {
        // RGBA8 cannot hold NaN; garbage shows as an alpha other than 1.
        for (std::size_t i = 3; i < image.rgba.size(); i += 4) ASSERT_EQ(image.rgba[i], 255) << "pixel " << i / 4;
    }
};

inline std::shared_ptr<const splat_lod::SplatCloud> shared(splat_lod::SplatCloud cloud) {
    return std::make_shared<const splat_lod::SplatCloud>(std::move(cloud));
}
