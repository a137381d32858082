// Stereo (docs/stereo.md): the two eyes of engine::stereo_eyes draw the selection of their centre, so they
// draw the same Gaussians at the same levels, where each eye selecting for itself would not; and an eye
// is the mono render from its own position with its own selection where the selection does not matter.
#include <array>
#include <cmath>
#include <vector>

#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "gpu_fixture.h"
#include "splat_lod/core/lod_selection.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/splat_renderer.h"
#include "splat_test_scenes.h"
#include "test_support.h"

namespace ref = splat_lod::reference;

namespace {

class SplatStereoTest : public engine::test::GpuTest {
protected:
    engine::test::SplatRenderHarness harness;
    splat_lod::SplatRenderer pass{harness.engine().renderer()};

    std::array<std::uint64_t, 4> drawn_per_level(const std::shared_ptr<const splat_lod::SplatCloud>& cloud,
                                                 const engine::CameraView& view) {
        harness.render({cloud}, view);
        return pass.latest_statistics()->per_level;
    }
};

}  // namespace

// A cloud of four levels whose upper coverage bounds sit 4 % either side of each Gaussian's switch as seen
// from the centre view: an eye 0.3 units to the side sees those coverages change by more than that, so
// an eye selecting for itself draws another set, while the stereo eyes draw the centre's exactly.
TEST_F(SplatStereoTest, BothEyesDrawTheCentresSelection) {
    const auto specs = engine::test::swirl_specs(600, 0.3f, 0.4f);
    splat_lod::SplatCloud cloud = engine::test::make_cloud(specs);
    const auto centre =
        engine::make_look_at_camera({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), 160, 120, 0.1f, 100.0f);
    const ref::ReferenceSettings settings;
    const auto ref_camera = ref::make_reference_camera(centre);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto p = ref::project_gaussian(cloud, i, glm::dmat4(1.0), ref_camera, settings);
        const glm::dvec3 c = p.cov2d - glm::dvec3(settings.dilation, 0.0, settings.dilation);
        const double coverage = splat_lod::pixel_coverage(c.x, c.y, c.z, p.opacity);
        cloud.lod_level[i] = static_cast<std::uint8_t>(1 + i % 4);
        // "Not too large" (levels 2–4) passes by 4 % or fails by 4 % from the centre; "not too small" is off.
        const double f = i % 2 == 0 ? 1.04 : 1.0 / 1.04;
        cloud.coverage_min[i] = -1.0f;
        cloud.coverage_max[i] = static_cast<float>(coverage / plugin_msgs::LodRule{}.rel_max * f);
    }
    const auto shared = std::make_shared<const splat_lod::SplatCloud>(std::move(cloud));
    harness.edit_lod([](plugin_msgs::LodSettings& lod) { lod.rule.transition_band = 0.0f; });
    pass.settings().frustum_culling = false;  // every Gaussian is inside all three views anyway

    const engine::StereoEyes eyes = engine::stereo_eyes(centre, 0.6f);
    const auto mono = drawn_per_level(shared, centre);
    EXPECT_EQ(drawn_per_level(shared, eyes.left), mono);
    EXPECT_EQ(drawn_per_level(shared, eyes.right), mono);
    engine::CameraView own = eyes.left;
    own.selection_view.reset();
    EXPECT_NE(drawn_per_level(shared, own), mono) << "the case is not vacuous";
    std::uint64_t drawn = 0;
    for (const auto n : mono) drawn += n;
    EXPECT_GT(drawn, 100u);
}

// Where the selection does not decide anything (a real capture, one level) an eye is exactly the mono
// render from its position; the two eyes differ (parallax).
TEST_F(SplatStereoTest, AnEyeIsTheMonoRenderFromItsPosition) {
    ENGINE_REQUIRE_SHARED_DATA();
    const auto real = engine::test::real_splat_scenes().front();
    const auto cloud = std::make_shared<const splat_lod::SplatCloud>(splat_lod::load_splat_file(real.path));
    const auto centre = engine::test::orbit_cameras(*cloud, real.up, 1, 200, 150).front();
    const engine::StereoEyes eyes = engine::stereo_eyes(centre, 0.063f);
    const engine::Image left = harness.render({cloud}, eyes.left), right = harness.render({cloud}, eyes.right);
    engine::CameraView own = eyes.left;
    own.selection_view.reset();
    EXPECT_EQ(left.rgba, harness.render({cloud}, own).rgba);
    EXPECT_LT(engine::compare_images(left, right).psnr_db, 60.0);
}
