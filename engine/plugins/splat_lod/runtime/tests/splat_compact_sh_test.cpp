// The project pass decodes the compact SH words as the CPU does (common_splat_storage.glsl against
// splat_lod/core/compact_gaussians.h) at every stored degree, each with its own layout: the GPU's
// compact frame against the double-precision reference drawing compact_round_trip() of the same cloud.
#include <cmath>

#include "engine/render/scene_camera.h"
#include "gpu_fixture.h"
#include "splat_lod/core/compact_gaussians.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace ref = splat_lod::reference;

namespace {

class SplatCompactShTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness harness;

    engine::Image reference(const splat_lod::SplatCloud& cloud, const engine::CameraView& camera) {
        const ref::ReferenceInstance instance{&cloud, glm::dmat4(1.0), splat_lod::kMaxShDegree};
        return ref::to_image8(ref::render_reference(std::span(&instance, 1), camera, ref::ReferenceSettings{}));
    }
};

// 300 swirled Gaussians whose higher bands are strong (0.35, 0.25 and 0.18 per band) and
// differ per Gaussian, coefficient and channel.
splat_lod::SplatCloud view_dependent_cloud(int degree) {
    splat_lod::SplatCloud cloud = engine::test::make_cloud(engine::test::swirl_specs(300, 0.3f, 0.6f));
    cloud.set_sh_degree(degree);
    for (std::size_t i = 0; i < cloud.size(); ++i)
        for (int k = 1; k <= splat_lod::sh_rest_coeffs(degree); ++k)
            for (int c = 0; c < 3; ++c)
                cloud.sh_rest_at(i, k, c) = (k < 4 ? 0.35f : (k < 9 ? 0.25f : 0.18f)) *
                                            std::sin(1.3f * float(i) + 2.1f * float(k) + 0.7f * float(c));
    return cloud;
}

}  // namespace

TEST_F(SplatCompactShTest, EveryStoredDegreeDrawsWhatTheCpuDecodes) {
    const auto camera = engine::make_look_at_camera({0.5f, 0.8f, 4.0f}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 160,
                                                    120, 0.1f, 100.0f);
    for (int degree = 1; degree <= 3; ++degree) {
        SCOPED_TRACE("degree " + std::to_string(degree));
        const auto cloud = std::make_shared<const splat_lod::SplatCloud>(view_dependent_cloud(degree));
        const engine::Image gpu = harness.render({cloud}, camera);
        const engine::Image stored = reference(splat_lod::compact_round_trip(*cloud, degree), camera);
        const auto d = engine::compare_images(gpu, stored);
        EXPECT_GE(d.psnr_db, 48.0);
        EXPECT_LE(d.max_channel_difference, 3);
        // The higher bands matter in this frame: without them it is far from what is drawn.
        splat_lod::SplatCloud dc_only = splat_lod::compact_round_trip(*cloud, degree);
        std::fill(dc_only.sh_rest.begin(), dc_only.sh_rest.end(), 0.0f);
        EXPECT_LT(engine::compare_images(reference(dc_only, camera), stored).psnr_db, 35.0);
    }
}
