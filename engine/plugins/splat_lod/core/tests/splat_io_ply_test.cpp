// INRIA PLY: writer/reader round trips, the reduced layout, ascii and type conversion, and the
// sanitise step (NaN/Inf and zero quaternions dropped and counted).
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"
#include "test_support.h"

using splat_io_test::error_of;
using splat_io_test::make_cloud;
using splat_lod::LoadReport;
using splat_lod::SplatCloud;

namespace {

std::vector<std::uint8_t> text_bytes(const std::string& s) {
    return {s.begin(), s.end()};
}

std::string header_of(const std::vector<std::uint8_t>& bytes) {
    const std::string text(bytes.begin(), bytes.end());
    return text.substr(0, text.find("end_header"));
}

void expect_same_cloud(const SplatCloud& a, const SplatCloud& b) {
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.sh_degree, b.sh_degree);
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a.positions[i], b.positions[i]) << i;
        ASSERT_EQ(a.log_scales[i], b.log_scales[i]) << i;
        ASSERT_EQ(a.sh_dc[i], b.sh_dc[i]) << i;
        ASSERT_EQ(a.opacity_logits[i], b.opacity_logits[i]) << i;
        // Already unit length; renormalising on load may move the last bit.
        ASSERT_NEAR(a.rotations[i].w, b.rotations[i].w, 1e-6f) << i;
        ASSERT_NEAR(a.rotations[i].x, b.rotations[i].x, 1e-6f) << i;
        ASSERT_NEAR(a.rotations[i].y, b.rotations[i].y, 1e-6f) << i;
        ASSERT_NEAR(a.rotations[i].z, b.rotations[i].z, 1e-6f) << i;
        ASSERT_EQ(a.lod_level[i], b.lod_level[i]) << i;
        ASSERT_EQ(a.coverage_min[i], b.coverage_min[i]) << i;
        ASSERT_EQ(a.coverage_max[i], b.coverage_max[i]) << i;
    }
    ASSERT_EQ(a.sh_rest, b.sh_rest);
    ASSERT_EQ(a.extras.size(), b.extras.size());
    for (std::size_t e = 0; e < a.extras.size(); ++e) {
        EXPECT_EQ(a.extras[e].name, b.extras[e].name);
        EXPECT_EQ(a.extras[e].values, b.extras[e].values);
    }
}

// A reduced-layout header for `count` vertices with the given "property <type> <name>" lines.
std::string reduced_header(const std::string& format, std::size_t count, const std::string& type = "float") {
    std::string h = "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(count) + "\n";
    for (const char* name : {"x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0", "scale_1", "scale_2",
                             "rot_0", "rot_1", "rot_2", "rot_3"})
        h += "property " + type + " " + name + "\n";
    return h + "end_header\n";
}

}  // namespace

TEST(SplatIoPly, RoundTripEveryShDegreeWithExtrasAndLodAttributes) {
    const auto dir = engine::test::output_dir("splat_io");
    for (int degree = 0; degree <= 3; ++degree) {
        SCOPED_TRACE("SH degree " + std::to_string(degree));
        const SplatCloud original = make_cloud(300, degree, 7u + static_cast<std::uint32_t>(degree), true, true);
        const auto path = dir / ("round_trip_sh" + std::to_string(degree) + ".ply");
        splat_lod::write_inria_ply(path, original);
        LoadReport report;
        const SplatCloud loaded = splat_lod::read_ply(path, &report);
        EXPECT_EQ(report.format, "INRIA PLY (binary_little_endian)");
        EXPECT_EQ(report.gaussians_in_file, 300u);
        EXPECT_EQ(report.loaded, 300u);
        EXPECT_EQ(report.dropped(), 0u);
        EXPECT_TRUE(report.warnings.empty());
        expect_same_cloud(original, loaded);
    }
}

TEST(SplatIoPly, WriterUsesTheInriaLayoutAndChannelMajorFRest) {
    SplatCloud cloud = make_cloud(2, 1, 3);
    for (int k = 1; k <= 3; ++k)
        for (int c = 0; c < 3; ++c) cloud.sh_rest_at(1, k, c) = static_cast<float>(10 * c + k);
    const auto bytes = splat_lod::encode_inria_ply(cloud);
    const std::string header = header_of(bytes);
    EXPECT_NE(header.find("property float nx\n"), std::string::npos);
    EXPECT_NE(header.find("property float f_rest_8\n"), std::string::npos);
    EXPECT_EQ(header.find("f_rest_9"), std::string::npos);
    EXPECT_EQ(header.find("lod_level"), std::string::npos) << "no LOD attributes when all are default";
    // Row 1, f_rest_0..8 start after x y z nx ny nz f_dc_0..2: R1 R2 R3 G1 G2 G3 B1 B2 B3.
    const std::size_t row = 4 * (17 + 9);
    const std::size_t data = std::string(bytes.begin(), bytes.end()).find("end_header\n") + 11;
    float f_rest[9];
    std::memcpy(f_rest, bytes.data() + data + row + 9 * 4, sizeof f_rest);
    const float expected[9] = {1, 2, 3, 11, 12, 13, 21, 22, 23};
    for (int i = 0; i < 9; ++i) EXPECT_EQ(f_rest[i], expected[i]) << "f_rest_" << i;
}

TEST(SplatIoPly, LodAttributesAreWrittenWhenAnyGaussianUsesThem) {
    SplatCloud cloud = make_cloud(3, 0, 4);
    cloud.coverage_max[2] = 12.5f;
    const std::string header = header_of(splat_lod::encode_inria_ply(cloud));
    EXPECT_NE(header.find("property float coverage_min\nproperty float coverage_max\nproperty uchar lod_level\n"),
              std::string::npos);
    const SplatCloud loaded = splat_lod::read_ply(splat_lod::encode_inria_ply(cloud), "lod.ply");
    EXPECT_EQ(loaded.coverage_max[2], 12.5f);
    EXPECT_EQ(loaded.coverage_min[2], -1.0f);
    EXPECT_EQ(loaded.lod_level[2], 1);
}

// A baked cloud's level handover travels in a header comment; a cloud that does not know it writes none,
// and a file from elsewhere (no comment, or a value this reader does not know) reads as unknown.
TEST(SplatIoPly, TheLevelHandoverRoundTripsInTheHeader) {
    using splat_lod::LevelHandover;
    SplatCloud cloud = make_cloud(3, 0, 4);
    cloud.coverage_max[2] = 12.5f;
    for (const LevelHandover handover : {LevelHandover::overlapping, LevelHandover::abutting}) {
        cloud.level_handover = handover;
        const auto bytes = splat_lod::encode_inria_ply(cloud);
        EXPECT_NE(header_of(bytes).find(std::string("comment splat_lod level_handover ") +
                                        splat_lod::level_handover_name(handover) + "\n"),
                  std::string::npos);
        EXPECT_EQ(splat_lod::read_ply(bytes, "lod.ply").level_handover, handover);
    }
    cloud.level_handover = LevelHandover::unknown;
    EXPECT_EQ(header_of(splat_lod::encode_inria_ply(cloud)).find("level_handover"), std::string::npos);
    // Without LOD attributes there are no levels to hand over: nothing is written.
    SplatCloud plain = make_cloud(3, 0, 4);
    plain.level_handover = LevelHandover::overlapping;
    EXPECT_EQ(header_of(splat_lod::encode_inria_ply(plain)).find("level_handover"), std::string::npos);
    // An unknown value is a warning, not an error.
    cloud.level_handover = LevelHandover::abutting;
    auto bytes = splat_lod::encode_inria_ply(cloud);
    const std::string text(bytes.begin(), bytes.end());
    const std::size_t at = text.find("abutting");
    ASSERT_NE(at, std::string::npos);
    std::memcpy(bytes.data() + at, "sideways", 8);
    LoadReport report;
    EXPECT_EQ(splat_lod::read_ply(bytes, "odd.ply", &report).level_handover, LevelHandover::unknown);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("sideways"), std::string::npos) << report.warnings[0];
    // Kept by a permutation; two clouds of different kinds appended are of no known kind.
    SplatCloud other = make_cloud(2, 0, 4);
    other.level_handover = LevelHandover::overlapping;
    EXPECT_EQ(other.permuted({1, 0}).level_handover, LevelHandover::overlapping);
    splat_lod::append_cloud(cloud, std::move(other));
    EXPECT_EQ(cloud.level_handover, LevelHandover::unknown);
}

TEST(SplatIoPly, ReducedLayoutOfTheDonut) {
    ENGINE_REQUIRE_DATA("splats/gshairlod-donut/fused.ply");
    LoadReport report;
    const SplatCloud cloud = splat_lod::read_ply(splat_io_test::real_splat("gshairlod-donut/fused.ply"), &report);
    EXPECT_EQ(cloud.size(), 45624u);
    EXPECT_EQ(report.gaussians_in_file, 45624u);
    EXPECT_EQ(cloud.sh_degree, 0);
    EXPECT_TRUE(cloud.extras.empty());
    EXPECT_FALSE(cloud.has_lod_attributes());
    for (const auto& r : cloud.rotations) ASSERT_NEAR(r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z, 1.0f, 1e-5f);
}

TEST(SplatIoPly, AsciiAndMixedPropertyTypesAreConverted) {
    std::string text =
        "ply\nformat ascii 1.0\ncomment mixed types\nelement vertex 2\n"
        "property double x\nproperty float y\nproperty short z\n"
        "property float f_dc_0\nproperty float f_dc_1\nproperty float f_dc_2\n"
        "property float opacity\nproperty float scale_0\nproperty float scale_1\n"
        "property float scale_2\nproperty uchar rot_0\nproperty char rot_1\n"
        "property float rot_2\nproperty float rot_3\nproperty ushort confidence\n"
        "element camera 1\nproperty float fov\nend_header\n"
        "1.5 -2 3 0.1 0.2 0.3 4 -1 -2 -3 2 0 0 0 7\n"
        "0 0 -7 0 0 0 -4 0 0 0 0 -3 0 0 65535\n0.8\n";
    LoadReport report;
    const SplatCloud cloud = splat_lod::read_ply(text_bytes(text), "mixed.ply", &report);
    EXPECT_EQ(report.format, "INRIA PLY (ascii)");
    ASSERT_EQ(cloud.size(), 2u);
    EXPECT_EQ(cloud.positions[0], glm::vec3(1.5f, -2.0f, 3.0f));
    EXPECT_EQ(cloud.positions[1].z, -7.0f);
    EXPECT_FLOAT_EQ(cloud.rotations[0].w, 1.0f) << "normalised from (2,0,0,0)";
    EXPECT_FLOAT_EQ(cloud.rotations[1].x, -1.0f) << "normalised from (0,-3,0,0)";
    ASSERT_NE(cloud.find_extra("confidence"), nullptr);
    EXPECT_EQ(cloud.find_extra("confidence")->values, (std::vector<float>{7.0f, 65535.0f}));
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("camera"), std::string::npos);
}

TEST(SplatIoPly, BigEndianDoubles) {
    std::string bytes = reduced_header("binary_big_endian", 1, "double");
    const double values[14] = {1, 2, 3, 0.5, 0.25, 0.125, -1, -2, -3, -4, 0, 0, 1, 0};
    for (double v : values) {
        unsigned char raw[8];
        std::memcpy(raw, &v, 8);
        for (int k = 7; k >= 0; --k) bytes.push_back(static_cast<char>(raw[k]));
    }
    const SplatCloud cloud = splat_lod::read_ply(text_bytes(bytes), "be.ply");
    ASSERT_EQ(cloud.size(), 1u);
    EXPECT_EQ(cloud.positions[0], glm::vec3(1, 2, 3));
    EXPECT_EQ(cloud.sh_dc[0], glm::vec3(0.5f, 0.25f, 0.125f));
    EXPECT_EQ(cloud.log_scales[0], glm::vec3(-2, -3, -4));
    EXPECT_EQ(cloud.rotations[0].y, 1.0f);
}

TEST(SplatIoPly, NonFiniteValuesAndZeroQuaternionsAreDroppedAndCounted) {
    SplatCloud cloud = make_cloud(40, 2, 11, true, true);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    cloud.positions[3].x = nan;
    cloud.positions[9].z = -inf;
    cloud.sh_rest_at(12, 8, 2) = nan;
    cloud.extras[1].values[20] = inf;
    cloud.opacity_logits[25] = nan;
    cloud.rotations[30] = {0, 0, 0, 0};
    cloud.rotations[31] = {1e-30f, 0, 0, 0};
    cloud.rotations[32] = {3, 0, 4, 0};  // non-unit: kept and normalised
    LoadReport report;
    const SplatCloud loaded = splat_lod::read_ply(splat_lod::encode_inria_ply(cloud), "nan.ply", &report);
    EXPECT_EQ(report.gaussians_in_file, 40u);
    EXPECT_EQ(report.dropped_non_finite, 5u);
    EXPECT_EQ(report.dropped_zero_rotation, 2u);
    EXPECT_EQ(report.loaded, 33u);
    ASSERT_EQ(loaded.size(), 33u);
    // Order is kept: original index 32 is now 32 - 7.
    EXPECT_FLOAT_EQ(loaded.rotations[25].w, 0.6f);
    EXPECT_FLOAT_EQ(loaded.rotations[25].y, 0.8f);
    EXPECT_EQ(loaded.positions[25], cloud.positions[32]);
    EXPECT_EQ(loaded.extras[0].values[25], cloud.extras[0].values[32]);
    EXPECT_EQ(loaded.lod_level[25], cloud.lod_level[32]);
}

TEST(SplatIoPly, ShDegreeComesFromTheFRestCount) {
    for (int degree = 0; degree <= 3; ++degree) {
        const SplatCloud loaded = splat_lod::read_ply(splat_lod::encode_inria_ply(make_cloud(5, degree, 1)), "d.ply");
        EXPECT_EQ(loaded.sh_degree, degree);
        EXPECT_EQ(loaded.sh_rest.size(), 5u * 3u * static_cast<std::size_t>(splat_lod::sh_rest_coeffs(degree)));
    }
    std::string h = reduced_header("ascii", 0);
    h.insert(h.find("end_header"), "property float f_rest_0\nproperty float f_rest_1\n");
    EXPECT_NE(error_of([&] { splat_lod::read_ply(text_bytes(h), "two_rest.ply"); }).find("two_rest.ply: 2 f_rest_*"),
              std::string::npos);
}

TEST(SplatIoPly, WriterLeavesNoTemporaryFiles) {
    const auto dir = engine::test::output_dir("splat_io") / "atomic";
    std::filesystem::remove_all(dir);
    splat_lod::write_inria_ply(dir / "a.ply", make_cloud(10, 0, 2));
    splat_lod::write_inria_ply(dir / "a.ply", make_cloud(20, 1, 2));
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        ++files;
        EXPECT_EQ(entry.path().filename(), "a.ply");
    }
    EXPECT_EQ(files, 1u);
    EXPECT_EQ(splat_lod::read_ply(dir / "a.ply").size(), 20u);
}

TEST(SplatIoPly, WriterRejectsUnwritableExtraNames) {
    SplatCloud cloud = make_cloud(1, 0, 1);
    cloud.add_extra("two words");
    EXPECT_NE(error_of([&] { splat_lod::encode_inria_ply(cloud); }).find("two words"), std::string::npos);
    cloud.extras.back().name = "opacity";
    EXPECT_NE(error_of([&] { splat_lod::encode_inria_ply(cloud); }).find("already used"), std::string::npos);
}
