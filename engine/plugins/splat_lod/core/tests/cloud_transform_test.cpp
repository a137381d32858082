// Rigid frame changes of a cloud (cloud_transform.h): every Gaussian's colour seen along R·d after the
// change is its colour along d before it, for every SH band; centres and covariances move with R; the
// rotation between two directions; and what is not a rotation is refused.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "splat_io_test_helpers.h"
#include "splat_lod/core/cloud_transform.h"
#include "splat_lod/core/reference_renderer.h"
#include "splat_lod/core/splat_math.h"

using splat_io_test::error_of;
using splat_io_test::make_cloud;

namespace {

glm::dmat3 covariance(const splat_lod::SplatCloud& cloud, std::size_t i) {
    const glm::dmat3 r = splat_lod::math::rotation_of(cloud.rotations[i]);
    const glm::dvec3 s = glm::exp(glm::dvec3(cloud.log_scales[i]));
    const glm::dmat3 scale(s.x, 0.0, 0.0, 0.0, s.y, 0.0, 0.0, 0.0, s.z);
    return r * scale * scale * glm::transpose(r);
}

TEST(CloudTransform, ColoursCentresAndCovariancesTurnWithTheFrame) {
    const splat_lod::SplatCloud original = make_cloud(40, 3, 11);
    std::mt19937 rng(5);
    std::normal_distribution<double> normal;
    for (int trial = 0; trial < 4; ++trial) {
        const glm::dvec3 axis = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
        const glm::dmat3 r = splat_lod::rotation_between(glm::dvec3(0, 1, 0), axis);
        const glm::dvec3 t(3.0, -2.0, 0.5);
        splat_lod::SplatCloud turned = original;
        splat_lod::transform_cloud(turned, r, t);
        for (std::size_t i = 0; i < original.size(); ++i) {
            const glm::dvec3 moved = r * glm::dvec3(original.positions[i]) + t;
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(turned.positions[i][k], moved[k], 1e-5);
            const glm::dmat3 expected = r * covariance(original, i) * glm::transpose(r), got = covariance(turned, i);
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 3; ++k)
                    EXPECT_NEAR(got[c][k], expected[c][k], 1e-5 + 1e-5 * std::fabs(expected[c][k]));
            for (int d = 0; d < 6; ++d) {
                const glm::dvec3 direction = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
                const glm::dvec3 before = splat_lod::reference::sh_colour_unclamped(original, i, 3, direction);
                const glm::dvec3 after = splat_lod::reference::sh_colour_unclamped(turned, i, 3, r * direction);
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(after[c], before[c], 1e-5) << "Gaussian " << i << " trial " << trial;
            }
        }
    }
}

TEST(CloudTransform, RotationBetweenDirectionsAndRefusals) {
    const glm::dmat3 half_turn = splat_lod::rotation_between({0, 1, 0}, {0, -1, 0});
    const glm::dvec3 down = half_turn * glm::dvec3(0, 1, 0);
    EXPECT_NEAR(down.y, -1.0, 1e-12);
    EXPECT_NEAR(glm::determinant(half_turn), 1.0, 1e-12);
    const glm::dmat3 to_z = splat_lod::rotation_between({0, 0, 1}, {0, 1, 0});
    const glm::dvec3 up = to_z * glm::dvec3(0, 0, 1);
    EXPECT_NEAR(up.y, 1.0, 1e-12);
    EXPECT_EQ(splat_lod::rotation_between({1, 0, 0}, {1, 0, 0}), glm::dmat3(1.0));
    splat_lod::SplatCloud cloud = make_cloud(3, 0, 1);
    const std::string message = error_of([&] { splat_lod::transform_cloud(cloud, glm::dmat3(2.0), glm::dvec3(0.0)); });
    EXPECT_NE(message.find("not a rotation"), std::string::npos) << message;
    const glm::dmat3 mirror(-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
    EXPECT_NE(error_of([&] { splat_lod::transform_cloud(cloud, mirror, glm::dvec3(0.0)); }).find("not a rotation"),
              std::string::npos);
}

}  // namespace
