// antimatter15 .splat and SPZ (v2, v3, v4) round trips with known values, the SPZ axis
// conversion (positions, rotations, SH parity), and format detection.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"
#include "test_support.h"

using splat_io_test::error_of;
using splat_io_test::make_cloud;
using splat_io_test::max_abs_diff;
using splat_lod::LoadReport;
using splat_lod::Rotation;
using splat_lod::SplatCloud;

namespace {

double sigmoid(double x) {
    return 1.0 / (1.0 + std::exp(-x));
}

double rotation_distance(const Rotation& a, const Rotation& b) {
    auto d = [&](double s) {
        return std::sqrt((a.w - s * b.w) * (a.w - s * b.w) + (a.x - s * b.x) * (a.x - s * b.x) +
                         (a.y - s * b.y) * (a.y - s * b.y) + (a.z - s * b.z) * (a.z - s * b.z));
    };
    return std::min(d(1.0), d(-1.0));
}

glm::mat3 rotation_matrix(const Rotation& q) {
    const float w = q.w, x = q.x, y = q.y, z = q.z;
    return glm::mat3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y),   // column 0
                     2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x),   // column 1
                     2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));  // column 2
}

// The 3DGS real SH basis (degree 3) at unit direction d, one channel.
float eval_sh(const SplatCloud& c, std::size_t i, int channel, glm::vec3 d) {
    const float x = d.x, y = d.y, z = d.z, xx = x * x, yy = y * y, zz = z * z;
    const float basis[16] = {0.28209479f,
                             -0.48860251f * y,
                             0.48860251f * z,
                             -0.48860251f * x,
                             1.09254843f * x * y,
                             -1.09254843f * y * z,
                             0.31539157f * (2 * zz - xx - yy),
                             -1.09254843f * x * z,
                             0.54627422f * (xx - yy),
                             -0.59004359f * y * (3 * xx - yy),
                             2.89061144f * x * y * z,
                             -0.45704580f * y * (4 * zz - xx - yy),
                             0.37317633f * z * (2 * zz - 3 * xx - 3 * yy),
                             -0.45704580f * x * (4 * zz - xx - yy),
                             1.44530572f * z * (xx - yy),
                             -0.59004359f * x * (xx - 3 * yy)};
    float sum = basis[0] * c.sh_dc[i][channel];
    for (int k = 1; k <= splat_lod::sh_rest_coeffs(c.sh_degree); ++k) sum += basis[k] * c.sh_rest_at(i, k, channel);
    return sum;
}

// Quantisation bounds of SPZ shared by all versions (see spz_reader.cpp for the encodings).
void expect_spz_quantisation(const SplatCloud& in, const SplatCloud& out) {
    const std::size_t n = in.size();
    ASSERT_EQ(out.size(), n);
    ASSERT_EQ(out.sh_degree, in.sh_degree);
    EXPECT_LE(max_abs_diff(n, [&](std::size_t i) { return glm::length(in.positions[i] - out.positions[i]); }),
              std::sqrt(3.0) * 0.5 / 4096 + 1e-5);
    EXPECT_LE(max_abs_diff(n, [&](std::size_t i) { return glm::length(in.log_scales[i] - out.log_scales[i]); }),
              std::sqrt(3.0) * 0.5 / 16 + 1e-5);
    EXPECT_LE(max_abs_diff(n, [&](std::size_t i) { return glm::length(in.sh_dc[i] - out.sh_dc[i]); }),
              std::sqrt(3.0) * 0.5 / (0.15 * 255) + 1e-5);
    EXPECT_LE(
        max_abs_diff(n, [&](std::size_t i) { return sigmoid(in.opacity_logits[i]) - sigmoid(out.opacity_logits[i]); }),
        0.5 / 255 + 1e-6);
    // SH: 1/128 steps, and +1 itself is clamped to 255/128 - 1.
    EXPECT_LE(max_abs_diff(in.sh_rest.size(), [&](std::size_t k) { return in.sh_rest[k] - out.sh_rest[k]; }),
              1.0 / 128 + 1e-6);
}

}  // namespace

TEST(SplatIoFormats, AntimatterSplatRoundTrip) {
    SplatCloud cloud = make_cloud(500, 0, 21);
    const auto path = engine::test::output_dir("splat_io") / "round_trip.splat";
    splat_lod::write_antimatter_splat(path, cloud);
    LoadReport report;
    const SplatCloud loaded = splat_lod::load_splat_file(path, &report);
    EXPECT_EQ(report.format, "antimatter15 .splat");
    ASSERT_EQ(loaded.size(), cloud.size());
    const std::size_t n = cloud.size();
    EXPECT_EQ(max_abs_diff(n, [&](std::size_t i) { return glm::length(cloud.positions[i] - loaded.positions[i]); }),
              0.0);
    EXPECT_LE(max_abs_diff(n, [&](std::size_t i) { return glm::length(cloud.log_scales[i] - loaded.log_scales[i]); }),
              1e-5);
    // Colour: 8 bits of 0.5 + C0·dc; opacity: 8 bits of sigmoid; quaternion: 8 bits of q·128 + 128.
    EXPECT_LE(max_abs_diff(n, [&](std::size_t i) { return glm::length(cloud.sh_dc[i] - loaded.sh_dc[i]); }),
              std::sqrt(3.0) * 0.5 / 255 / splat_lod::kShC0 + 1e-5);
    EXPECT_LE(
        max_abs_diff(
            n, [&](std::size_t i) { return sigmoid(cloud.opacity_logits[i]) - sigmoid(loaded.opacity_logits[i]); }),
        0.5 / 255 + 1e-6);
    EXPECT_LE(
        max_abs_diff(n, [&](std::size_t i) { return rotation_distance(cloud.rotations[i], loaded.rotations[i]); }),
        2 * 2 * (1.0 / 128));
}

TEST(SplatIoFormats, AntimatterSplatZeroScaleAndNanAreDroppedAndCounted) {
    SplatCloud cloud = make_cloud(10, 0, 5);
    cloud.positions[2].y = std::nanf("");
    cloud.log_scales[4].x = -200.0f;  // exp underflows to a stored scale of 0: log(0) = -inf
    LoadReport report;
    const auto loaded = splat_lod::read_antimatter_splat(splat_lod::encode_antimatter_splat(cloud), "x.splat", &report);
    EXPECT_EQ(loaded.size(), 8u);
    EXPECT_EQ(report.dropped_non_finite, 2u);
}

TEST(SplatIoFormats, SpzV3AndV4RoundTripEveryShDegree) {
    for (int version : {3, 4})
        for (int degree = 0; degree <= 3; ++degree) {
            SCOPED_TRACE("SPZ v" + std::to_string(version) + ", SH degree " + std::to_string(degree));
            const SplatCloud cloud = make_cloud(300, degree, 40u + static_cast<std::uint32_t>(degree));
            LoadReport report;
            const SplatCloud loaded = splat_lod::read_spz(splat_io_test::encode_spz(cloud, version), "t.spz", &report);
            EXPECT_EQ(report.format, version == 4 ? "SPZ v4 (zstd)" : "SPZ v3 (gzip)");
            expect_spz_quantisation(cloud, loaded);
            // Smallest three: three components within 0.5·(1/sqrt2)/511 = δ, the rebuilt one within 4.2δ.
            const double delta = 0.5 * 0.70710678 / 511;
            EXPECT_LE(
                max_abs_diff(cloud.size(),
                             [&](std::size_t i) { return rotation_distance(cloud.rotations[i], loaded.rotations[i]); }),
                4.6 * delta + 1e-6);
        }
}

TEST(SplatIoFormats, SpzV2RoundTrip) {
    SplatCloud cloud = make_cloud(300, 1, 77);
    LoadReport report;
    const SplatCloud loaded = splat_lod::read_spz(splat_io_test::encode_spz(cloud, 2), "v2.spz", &report);
    EXPECT_EQ(report.format, "SPZ v2 (gzip)");
    expect_spz_quantisation(cloud, loaded);
    // x, y, z in 8 bits (δ = 0.5/127.5) with w >= 0 rebuilt: well conditioned while |w| is not small.
    const double delta = 0.5 / 127.5;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (std::fabs(cloud.rotations[i].w) < 0.5f) continue;
        ASSERT_LE(rotation_distance(cloud.rotations[i], loaded.rotations[i]),
                  2 * std::sqrt(3.0) * delta / 0.5 + 2 * delta)
            << i;
    }
}

TEST(SplatIoFormats, SpzAxisConversionIsARotationByPiAboutX) {
    const SplatCloud original = make_cloud(50, 3, 9);
    SplatCloud converted = original;
    splat_lod::convert_spz_axes_to_ply(converted);
    const glm::mat3 m(1, 0, 0, 0, -1, 0, 0, 0, -1);
    std::mt19937 rng(3);
    std::normal_distribution<float> normal;
    for (std::size_t i = 0; i < original.size(); ++i) {
        EXPECT_EQ(converted.positions[i], m * original.positions[i]);
        // Covariance R S S Rᵀ maps to M Σ M: the rotation must become M R M.
        const glm::mat3 expected = m * rotation_matrix(original.rotations[i]) * m;
        const glm::mat3 actual = rotation_matrix(converted.rotations[i]);
        for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(expected[c] - actual[c]), 1e-5f);
        // View-dependent colour seen along d must be seen along M d after conversion.
        for (int trial = 0; trial < 4; ++trial) {
            const glm::vec3 d = glm::normalize(glm::vec3(normal(rng), normal(rng), normal(rng)));
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_NEAR(eval_sh(original, i, ch, d), eval_sh(converted, i, ch, m * d), 1e-5f);
        }
    }
    splat_lod::convert_spz_axes_to_ply(converted);
    EXPECT_EQ(converted.positions, original.positions) << "the conversion is its own inverse";
    EXPECT_EQ(converted.sh_rest, original.sh_rest);
}

TEST(SplatIoFormats, DetectionByContentThenExtension) {
    ENGINE_REQUIRE_SHARED_DATA();
    using F = splat_lod::SplatFileFormat;
    const auto real = splat_io_test::real_splat;
    EXPECT_EQ(splat_lod::detect_splat_format(real("playcanvas-engine/biker.spz")), F::spz);
    EXPECT_EQ(splat_lod::detect_splat_format(real("playcanvas-engine/guitar.compressed.ply")), F::ply);
    EXPECT_EQ(splat_lod::detect_splat_format(real("playcanvas-engine/playcanvas-logo-sog")), F::sog);
    EXPECT_EQ(splat_lod::detect_splat_format(real("playcanvas-engine/playcanvas-logo-sog/meta.json")), F::sog);
    const auto dir = engine::test::output_dir("splat_io");
    splat_lod::write_antimatter_splat(dir / "detect.splat", make_cloud(3, 0, 1));
    EXPECT_EQ(splat_lod::detect_splat_format(dir / "detect.splat"), F::antimatter_splat);
    // A PLY saved under another extension is still found by its magic.
    splat_lod::write_inria_ply(dir / "ply_as.bin", make_cloud(3, 0, 1));
    EXPECT_EQ(splat_lod::load_splat_file(dir / "ply_as.bin").size(), 3u);
    const std::string unknown = error_of([&] { splat_lod::load_splat_file(dir / "detect.splat.unknown"); });
    EXPECT_NE(unknown.find("detect.splat.unknown"), std::string::npos) << unknown;
    // A folder with lod-meta.json is a streamed SOG (capture_source_test.cpp reads it).
    EXPECT_EQ(splat_lod::detect_splat_format(real("playcanvas-engine/playbot-lod-sog")), F::streamed_sog);
}
