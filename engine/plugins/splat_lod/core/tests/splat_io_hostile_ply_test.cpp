// Hostile PLY input (INRIA, compressed) and .splat: truncation, lying counts, broken headers,
// NaN values. Every failure must be an engine::Error that names the file.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"
#include "test_support.h"

using splat_io_test::error_of;
using splat_io_test::make_cloud;
using splat_lod::LoadReport;

namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes text_bytes(const std::string& s) {
    return {s.begin(), s.end()};
}

// Replaces the first occurrence of `from` in the file's bytes.
Bytes replaced(const Bytes& bytes, const std::string& from, const std::string& to) {
    std::string text(bytes.begin(), bytes.end());
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    return text_bytes(text);
}

std::string read_ply_error(const Bytes& bytes, const std::string& name) {
    return error_of([&] { splat_lod::read_ply(bytes, name); });
}

void expect_error(const std::string& error, const std::string& name, const std::string& fragment) {
    EXPECT_EQ(error.rfind(name + ": ", 0), 0u) << "message must start with the file name: " << error;
    EXPECT_NE(error.find(fragment), std::string::npos) << "expected \"" << fragment << "\" in: " << error;
}

// Cuts at a spread of offsets through the header and the data; each must fail cleanly.
std::vector<std::size_t> cut_points(std::size_t size) {
    return {0, 1, 3, 4, 10, 50, 200, 700, 1500, size / 3, size / 2, size - 33, size - 1};
}

std::string reduced_header(std::size_t count) {
    std::string h = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(count) + "\n";
    for (const char* name : {"x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0", "scale_1", "scale_2",
                             "rot_0", "rot_1", "rot_2", "rot_3"})
        h += std::string("property float ") + name + "\n";
    return h + "end_header\n";
}

}  // namespace

TEST(SplatIoHostilePly, TruncatedRealFilesFailWithTheFileName) {
    const char* const files[] = {"gshairlod-donut/fused.ply", "playcanvas-engine/biker.compressed.ply",
                                 "playcanvas-engine/test-fixture-64.compressed.ply"};
    for (const char* file : files) ENGINE_REQUIRE_DATA(std::string("splats/") + file);
    for (const char* file : files) {
        const Bytes bytes = engine::read_binary_file(splat_io_test::real_splat(file));
        const std::string name = std::filesystem::path(file).filename().string();
        for (std::size_t cut : cut_points(bytes.size())) {
            SCOPED_TRACE(name + " cut at " + std::to_string(cut));
            const std::string error =
                read_ply_error(Bytes(bytes.begin(), bytes.begin() + static_cast<long>(cut)), name);
            EXPECT_EQ(error.rfind(name + ": ", 0), 0u) << error;
        }
    }
}

TEST(SplatIoHostilePly, LyingVertexCounts) {
    ENGINE_REQUIRE_DATA("splats/gshairlod-donut/fused.ply");
    ENGINE_REQUIRE_DATA("splats/playcanvas-engine/biker.compressed.ply");
    const Bytes donut = engine::read_binary_file(splat_io_test::real_splat("gshairlod-donut/fused.ply"));
    expect_error(read_ply_error(replaced(donut, "vertex 45624", "vertex 45625"), "d.ply"), "d.ply",
                 "offset 361: element \"vertex\" needs 2555000 bytes (45625 rows of 56)");
    expect_error(read_ply_error(replaced(donut, "vertex 45624", "vertex 18446744073709551615"), "d.ply"), "d.ply",
                 "overflows 64 bits");
    expect_error(read_ply_error(replaced(donut, "vertex 45624", "vertex 184467440737095516150"), "d.ply"), "d.ply",
                 "bad count");
    expect_error(read_ply_error(replaced(donut, "vertex 45624", "vertex -1"), "d.ply"), "d.ply", "bad count");
    // Fewer rows than the data hold is readable: the rest is reported, not silently used.
    LoadReport report;
    EXPECT_EQ(splat_lod::read_ply(replaced(donut, "vertex 45624", "vertex 45623"), "d.ply", &report).size(), 45623u);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("56 bytes after the last element"), std::string::npos);

    const Bytes biker = engine::read_binary_file(splat_io_test::real_splat("playcanvas-engine/biker.compressed.ply"));
    // One more chunk row shifts the vertex data: the file is now too short for it.
    expect_error(read_ply_error(replaced(biker, "chunk 597", "chunk 598"), "b.ply"), "b.ply",
                 "element \"vertex\" needs 2443936 bytes");
    expect_error(read_ply_error(replaced(biker, "chunk 597", "chunk 596"), "b.ply"), "b.ply",
                 "chunk element has 596 rows but 152746 Gaussians need 597");
    expect_error(read_ply_error(replaced(biker, "vertex 152746", "vertex 152747"), "b.ply"), "b.ply", "needs");
    expect_error(read_ply_error(replaced(biker, "vertex 152746", "vertex 4611686018427387904"), "b.ply"), "b.ply",
                 "overflows 64 bits");
}

TEST(SplatIoHostilePly, BrokenHeaders) {
    const Bytes good = splat_lod::encode_inria_ply(make_cloud(4, 1, 3));
    struct Case {
        std::string from, to, fragment;
    };
    const Case cases[] = {
        {"end_header", "end_headr", "unexpected header line \"end_headr\""},
        {"ply\n", "plx\n", "not a PLY file"},
        {"property float opacity", "property half opacity", "unknown property type \"half\""},
        {"property float opacity", "property list uchar int opacity", "list properties are not supported"},
        {"property float opacity", "property float scale_0", "duplicate property \"scale_0\""},
        {"property float opacity", "property float opacities", "no property \"opacity\""},
        {"property float f_rest_8\n", "", "8 f_rest_*"},
        {"property float f_rest_8\n", "property float f_rest_9\n", "not numbered 0..8"},
        {"format binary_little_endian 1.0", "format binary_middle_endian 1.0", "unknown format"},
        {"format binary_little_endian 1.0", "format binary_little_endian 2.0", "unsupported PLY version"},
        {"format binary_little_endian 1.0\n", "", "no format line"},
        {"element vertex 4", "element vertex", "malformed element line"},
        {"element vertex 4\n", "", "property before any element"},
        {"element vertex", "element face 1\nproperty int a\nelement vertex", "needs"},
        {"comment", "colour", "unexpected header line"},
        {"element vertex", "element vertex 1\nelement vertex", "duplicate element"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.from + " -> " + c.to);
        expect_error(read_ply_error(replaced(good, c.from, c.to), "h.ply"), "h.ply", c.fragment);
    }
    // A header with no newline at all, and a 2 MiB comment line that hides end_header.
    expect_error(read_ply_error(text_bytes("ply"), "h.ply"), "h.ply", "no end_header");
    expect_error(read_ply_error(text_bytes("ply\ncomment " + std::string(2 << 20, 'x') + "\nend_header\n"), "h.ply"),
                 "h.ply", "no end_header");
    expect_error(read_ply_error(text_bytes("ply\nformat binary_little_endian 1.0\nend_header\n"), "h.ply"), "h.ply",
                 "no \"vertex\" element");
}

TEST(SplatIoHostilePly, AsciiValuesAreCheckedBeforeAllocating) {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nend_header\n";
    expect_error(read_ply_error(text_bytes(header + "1 2 3\n"), "a.ply"), "a.ply", "ascii values");
    std::string small = reduced_header(2);
    small.replace(small.find("binary_little_endian"), 20, "ascii");
    expect_error(
        read_ply_error(text_bytes(small + "1 2 3 0 0 0 1 0 0 0 1 0 0 0\n1 2 3" + std::string(40, ' ')), "a.ply"),
        "a.ply", "ascii data end after 17 of 28 values");
    expect_error(
        read_ply_error(text_bytes(small + "1 2 3 0 0 0 1 0 0 0 1 0 0 0\n1 2 3 0 0 0 1 0 0 0 1 0 0 zero\n"), "a.ply"),
        "a.ply", "bad ascii value \"zero\"");
    // nan/inf parse as values; sanitise drops those Gaussians.
    LoadReport report;
    const auto cloud = splat_lod::read_ply(
        text_bytes(small + "nan 2 3 0 0 0 1 0 0 0 1 0 0 0\n1 2 3 0 0 0 inf 0 0 0 1 0 0 0\n"), "a.ply", &report);
    EXPECT_EQ(cloud.size(), 0u);
    EXPECT_EQ(report.dropped_non_finite, 2u);
}

TEST(SplatIoHostilePly, NanChunkBoundsDropTheirGaussiansInCompressedPly) {
    ENGINE_REQUIRE_DATA("splats/playcanvas-engine/test-fixture-64.compressed.ply");
    Bytes fixture =
        engine::read_binary_file(splat_io_test::real_splat("playcanvas-engine/test-fixture-64.compressed.ply"));
    const std::string text(fixture.begin(), fixture.end());
    const std::size_t data = text.find("end_header\n") + 11;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(fixture.data() + data, &nan, 4);  // chunk 0 min_x
    LoadReport report;
    const auto cloud = splat_lod::read_ply(fixture, "fixture.ply", &report);
    EXPECT_EQ(cloud.size(), 0u);
    EXPECT_EQ(report.gaussians_in_file, 64u);
    EXPECT_EQ(report.dropped_non_finite, 64u);
}

TEST(SplatIoHostilePly, CompressedPlyWithWrongPropertyTypes) {
    ENGINE_REQUIRE_DATA("splats/playcanvas-engine/test-fixture-64.compressed.ply");
    const Bytes fixture =
        engine::read_binary_file(splat_io_test::real_splat("playcanvas-engine/test-fixture-64.compressed.ply"));
    // Same byte size, wrong meaning: a float packed field must be rejected, not reinterpreted.
    expect_error(read_ply_error(replaced(fixture, "uint packed_rotation", "float packed_rotation"), "f.ply"), "f.ply",
                 "\"packed_rotation\" has type float");
    expect_error(read_ply_error(replaced(fixture, "float min_scale_x", "float min_scale_q"), "f.ply"), "f.ply",
                 "no property \"min_scale_x\"");
    expect_error(read_ply_error(replaced(fixture, "element sh 64", "element sh 63"), "f.ply"), "f.ply",
                 "sh element has 63 rows");
}

TEST(SplatIoHostileSplat, SizeNotAMultipleOfTheRecordAndNanValues) {
    const Bytes bytes = splat_lod::encode_antimatter_splat(make_cloud(20, 0, 8));
    for (std::size_t cut : {1u, 31u, 33u, 100u, 639u})
        expect_error(error_of([&] { splat_lod::read_antimatter_splat(std::span(bytes).first(cut), "s.splat"); }),
                     "s.splat", "not a multiple of the 32-byte");
    // Cuts on a record boundary are valid files with fewer Gaussians: nothing to detect.
    EXPECT_EQ(splat_lod::read_antimatter_splat(std::span(bytes).first(64), "s.splat").size(), 2u);
    EXPECT_TRUE(splat_lod::read_antimatter_splat(Bytes{}, "empty.splat").empty());
}
