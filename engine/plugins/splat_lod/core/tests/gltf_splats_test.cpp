// KHR_gaussian_splatting: the writer's files read back to the same Gaussians and rewrite to the same
// bytes; quantised attributes decode within their step; node transforms move and reshape the
// Gaussians as applying the matrix by hand does; several nodes and primitives merge into one cloud.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/file_io.h"
#include "gltf_splats_test_helpers.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"
#include "test_support.h"

using splat_io_test::make_cloud;
using splat_lod::SplatCloud;

namespace {

std::span<const std::uint8_t> span_of(const std::vector<std::uint8_t>& v) {
    return {v.data(), v.size()};
}

glm::dmat3 covariance(const SplatCloud& c, std::size_t i) {
    const auto& r = c.rotations[i];
    const glm::dmat3 rot = glm::mat3_cast(glm::dquat(r.w, r.x, r.y, r.z));
    const glm::dvec3 s = glm::exp(glm::dvec3(c.log_scales[i]));
    const glm::dmat3 m = rot * glm::dmat3(glm::dvec3(s.x, 0, 0), glm::dvec3(0, s.y, 0), glm::dvec3(0, 0, s.z));
    return m * glm::transpose(m);
}

// Every field of a and b: rotations up to sign, log-scales and logits within the given tolerances.
void expect_same_gaussians(const SplatCloud& a, const SplatCloud& b, double pos_tol, double rot_tol, double scale_tol,
                           double logit_tol) {
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.sh_degree, b.sh_degree);
    for (std::size_t i = 0; i < a.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(a.positions[i][c], b.positions[i][c], pos_tol) << i;
            EXPECT_NEAR(a.log_scales[i][c], b.log_scales[i][c], scale_tol) << i;
            EXPECT_EQ(a.sh_dc[i][c], b.sh_dc[i][c]) << i;
        }
        const auto &p = a.rotations[i], &q = b.rotations[i];
        const double dot = double(p.w) * q.w + double(p.x) * q.x + double(p.y) * q.y + double(p.z) * q.z;
        EXPECT_NEAR(std::abs(dot), 1.0, rot_tol) << i;
        EXPECT_NEAR(a.opacity_logits[i], b.opacity_logits[i], logit_tol) << i;
    }
    EXPECT_EQ(a.sh_rest, b.sh_rest);
    EXPECT_EQ(a.lod_level, b.lod_level);
    EXPECT_EQ(a.coverage_min, b.coverage_min);
    EXPECT_EQ(a.coverage_max, b.coverage_max);
    ASSERT_EQ(a.extras.size(), b.extras.size());
    for (std::size_t k = 0; k < a.extras.size(); ++k) {
        EXPECT_EQ(a.extras[k].name, b.extras[k].name);
        EXPECT_EQ(a.extras[k].values, b.extras[k].values);
    }
}

TEST(GltfSplats, WrittenFileReadsBackToTheSameGaussians) {
    for (const bool binary : {true, false})
        for (int degree = 0; degree <= 3; ++degree) {
            const SplatCloud cloud = make_cloud(300, degree, 7u + static_cast<std::uint32_t>(degree), true, true);
            const auto bytes = splat_lod::encode_gltf_splats(cloud, binary);
            splat_lod::LoadReport report;
            const SplatCloud back = splat_lod::read_gltf_splats(span_of(bytes), binary ? "a.glb" : "a.gltf", &report);
            EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
            EXPECT_EQ(report.format, "glTF KHR_gaussian_splatting");
            expect_same_gaussians(cloud, back, 0.0, 1e-6, 1e-5, 1e-4);
        }
}

TEST(GltfSplats, ReadAndWrittenAgainGivesTheSameBytes) {
    for (const bool binary : {true, false})
        for (int degree = 0; degree <= 3; ++degree) {
            const SplatCloud cloud =
                make_cloud(500, degree, 11u + static_cast<std::uint32_t>(degree), degree == 2, true);
            const auto first = splat_lod::encode_gltf_splats(cloud, binary);
            const auto again = splat_lod::encode_gltf_splats(splat_lod::read_gltf_splats(span_of(first), "a"), binary);
            EXPECT_EQ(first, again) << "binary " << binary << " degree " << degree;
        }
}

// A baked cloud's level handover travels in the splat primitive's extras, as in the PLY header: each
// kind reads back, a cloud without LOD attributes or of unknown handover writes none, and an unknown
// name is a warning that reads as unknown.
TEST(GltfSplats, TheLevelHandoverTravelsInThePrimitivesExtras) {
    using splat_lod::LevelHandover;
    for (const bool binary : {true, false})
        for (const auto handover : {LevelHandover::overlapping, LevelHandover::abutting, LevelHandover::unknown}) {
            SplatCloud cloud = make_cloud(50, 0, 5u, true, false);
            cloud.level_handover = handover;
            const auto bytes = splat_lod::encode_gltf_splats(cloud, binary);
            splat_lod::LoadReport report;
            const SplatCloud back = splat_lod::read_gltf_splats(span_of(bytes), "a.glb", &report);
            EXPECT_EQ(back.level_handover, handover) << splat_lod::level_handover_name(handover);
            EXPECT_TRUE(report.warnings.empty());
            const std::string text(bytes.begin(), bytes.end());
            EXPECT_EQ(text.find("splat_lod_level_handover") != std::string::npos, handover != LevelHandover::unknown);
            EXPECT_EQ(splat_lod::encode_gltf_splats(back, binary), bytes) << "the same bytes again";
        }
    SplatCloud plain = make_cloud(50, 0, 5u, false, false);
    plain.level_handover = LevelHandover::overlapping;  // no LOD attributes: nothing to hand over
    const auto plain_bytes = splat_lod::encode_gltf_splats(plain, false);
    EXPECT_EQ(std::string(plain_bytes.begin(), plain_bytes.end()).find("splat_lod_level_handover"), std::string::npos);
    SplatCloud baked = make_cloud(50, 0, 5u, true, false);
    baked.level_handover = LevelHandover::abutting;
    const auto bytes = splat_lod::encode_gltf_splats(baked, false);
    std::string text(bytes.begin(), bytes.end());
    text.replace(text.find("\"abutting\""), 10, "\"sideways\"");
    splat_lod::LoadReport report;
    const SplatCloud back =
        splat_lod::read_gltf_splats(span_of(std::vector<std::uint8_t>(text.begin(), text.end())), "a.gltf", &report);
    EXPECT_EQ(back.level_handover, LevelHandover::unknown);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings.front().find("unknown level handover \"sideways\""), std::string::npos)
        << report.warnings.front();
}

// A real capture: PLY → .glb file → load_splat_file gives the PLY's Gaussians, and the .glb rewrites
// to the same bytes.
TEST(GltfSplats, GlbOfARealCaptureLoadsAsItsPly) {
    for (const char* name : {"gshairlod-donut/fused.ply", "playcanvas-engine/guitar.compressed.ply"}) {
        const auto ply = splat_io_test::real_splat(name);
        if (!std::filesystem::exists(ply)) GTEST_SKIP() << "test data file " << ply << " not found";
        const SplatCloud cloud = splat_lod::read_ply(ply);
        const auto glb = engine::test::output_dir("gltf_splats") / "capture.glb";
        splat_lod::write_gltf_splats(glb, cloud);
        EXPECT_EQ(splat_lod::detect_splat_format(glb), splat_lod::SplatFileFormat::gltf);
        splat_lod::LoadReport report;
        const SplatCloud back = splat_lod::load_splat_file(glb, &report);
        EXPECT_EQ(report.dropped(), 0u);
        expect_same_gaussians(cloud, back, 0.0, 1e-6, 2e-5, 1e-4);
        const auto again = splat_lod::encode_gltf_splats(back, true);
        EXPECT_EQ(engine::read_binary_file(glb), again) << name;
    }
}

TEST(GltfSplats, QuantisedAttributesDecodeWithinTheirStep) {
    using namespace gltf_test;
    struct Case {
        Encodings enc;
        double rot_tol, scale_tol, opacity_tol;
    };
    const Case cases[] = {
        {{{kByte, true}, {kFloat, false}, {kUByte, true}}, 0.03, 1e-5, 0.5 / 255},
        {{{kShort, true}, {kUShort, true}, {kUShort, true}}, 1e-4, 0.5 / 65535, 0.5 / 65535},
        {{{kFloat, false}, {kUByte, true}, {kFloat, false}}, 1e-6, 0.5 / 255, 1e-6},
        {{{kFloat, false}, {kUShort, false}, {kFloat, false}}, 1e-6, 0.5, 1e-6},
    };
    SplatCloud cloud = make_cloud(200, 1, 5);
    for (auto& s : cloud.log_scales) s = glm::clamp(s, glm::vec3(-5.0f), glm::vec3(-0.01f));  // linear in (0, 1)
    for (const Case& c : cases) {
        SplatCloud source = cloud;
        if (c.scale_tol >= 0.5)  // unnormalised integers: scales of whole units
            for (auto& s : source.log_scales) s = glm::log(glm::round(glm::exp(s) * 400.0f) + 1.0f);
        Builder b;
        b.primitive(source, c.enc);
        splat_lod::LoadReport report;
        const SplatCloud back = splat_lod::read_gltf_splats(span_of(b.file()), "q.gltf", &report);
        ASSERT_EQ(back.size(), source.size());
        for (std::size_t i = 0; i < back.size(); ++i) {
            const auto &p = source.rotations[i], &q = back.rotations[i];
            EXPECT_NEAR(std::abs(double(p.w) * q.w + double(p.x) * q.x + double(p.y) * q.y + double(p.z) * q.z), 1.0,
                        c.rot_tol);
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(std::exp(back.log_scales[i][k]), std::exp(source.log_scales[i][k]), c.scale_tol + 1e-6);
            const auto sig = [](float x) { return 1.0 / (1.0 + std::exp(-double(x))); };
            EXPECT_NEAR(sig(back.opacity_logits[i]), sig(source.opacity_logits[i]), c.opacity_tol + 1e-6);
            EXPECT_EQ(back.sh_dc[i], source.sh_dc[i]);
        }
    }
}

// A node with translation, rotation and scale (uniform, then not) gives the Gaussians moved and
// reshaped: positions M·p + t and covariances M·Σ·Mᵀ.
TEST(GltfSplats, NodeTransformsApplyToPositionsAndCovariances) {
    const SplatCloud cloud = make_cloud(100, 1, 3);
    for (const std::vector<double>& scale : {std::vector<double>{2, 2, 2}, std::vector<double>{0.5, 3, 1.5}}) {
        gltf_test::Builder b;
        b.primitive(cloud);
        const glm::dquat turn = glm::angleAxis(0.7, glm::normalize(glm::dvec3(1, 2, -0.5)));
        b.doc["nodes"][0]["translation"] = {1.5, -2, 4};
        b.doc["nodes"][0]["rotation"] = {turn.x, turn.y, turn.z, turn.w};
        b.doc["nodes"][0]["scale"] = scale;
        splat_lod::LoadReport report;
        const SplatCloud back = splat_lod::read_gltf_splats(span_of(b.file()), "t.gltf", &report);
        ASSERT_EQ(back.size(), cloud.size());
        ASSERT_FALSE(report.warnings.empty());
        EXPECT_NE(report.warnings.back().find("not rotated"), std::string::npos) << report.warnings.back();
        const glm::dmat3 m = glm::mat3_cast(turn) * glm::dmat3(glm::dvec3(scale[0], 0, 0), glm::dvec3(0, scale[1], 0),
                                                               glm::dvec3(0, 0, scale[2]));
        for (std::size_t i = 0; i < cloud.size(); ++i) {
            const glm::dvec3 p = m * glm::dvec3(cloud.positions[i]) + glm::dvec3(1.5, -2, 4);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.positions[i][c], p[c], 1e-5);
            const glm::dmat3 want = m * covariance(cloud, i) * glm::transpose(m);
            const glm::dmat3 got = covariance(back, i);
            const double size = std::max({want[0][0], want[1][1], want[2][2]});
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c][r], want[c][r], 1e-4 * size) << i;
        }
    }
}

// Two nodes (the second a child of the first, so its transform composes) instance two meshes; the
// second mesh has a triangle primitive, which is not a splat and is skipped, and a second splat primitive.
TEST(GltfSplats, SeveralNodesAndPrimitivesMergeIntoOneCloud) {
    const SplatCloud a = make_cloud(10, 0, 1), b = make_cloud(20, 2, 2, false, true), c = make_cloud(5, 1, 3);
    gltf_test::Builder builder;
    builder.primitive(a, {}, 0);
    builder.doc["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"mode", 4}}}}});
    builder.primitive(b, {}, 1);
    builder.primitive(c, {}, 1);
    builder.doc["nodes"] = {{{"mesh", 0}, {"translation", {10, 0, 0}}, {"children", {1}}},
                            {{"mesh", 1}, {"translation", {0, 5, 0}}}};
    const SplatCloud out = splat_lod::read_gltf_splats(span_of(builder.file()), "m.gltf");
    ASSERT_EQ(out.size(), 35u);
    EXPECT_EQ(out.sh_degree, 2);
    EXPECT_FLOAT_EQ(out.positions[0].x, a.positions[0].x + 10.0f);
    EXPECT_FLOAT_EQ(out.positions[10].y, b.positions[0].y + 5.0f);
    EXPECT_FLOAT_EQ(out.positions[10].x, b.positions[0].x + 10.0f);
    EXPECT_FLOAT_EQ(out.positions[30].z, c.positions[0].z);
    EXPECT_EQ(out.sh_rest_at(10, 8, 2), b.sh_rest_at(0, 8, 2));
    EXPECT_EQ(out.sh_rest_at(30, 3, 1), c.sh_rest_at(0, 3, 1));
    EXPECT_EQ(out.sh_rest_at(0, 3, 1), 0.0f);
}

// KHR_gaussian_splatting_compression_spz_2: the SPZ stream of a buffer view, in glTF's left-up-front axes
// (SPZ's right-up-back turned by pi about y: x and z negated, with the SH coefficients odd in x and z).
TEST(GltfSplats, SpzCompressedPrimitiveDecodesInGltfAxes) {
    const SplatCloud cloud = make_cloud(20, 1, 21);
    const auto spz = splat_io_test::encode_spz(cloud, 2);
    const SplatCloud want = splat_lod::read_spz(span_of(spz), "x.spz");
    gltf_test::Builder b;
    b.bytes = spz;
    b.doc["bufferViews"].push_back({{"buffer", 0}, {"byteLength", spz.size()}});
    b.doc["accessors"].push_back({{"componentType", 5126}, {"count", 20}, {"type", "VEC3"}});
    const nlohmann::json spz_ext = {{"KHR_gaussian_splatting_compression_spz_2", {{"bufferView", 0}}}};
    b.doc["meshes"][0]["primitives"].push_back(
        {{"attributes", {{"POSITION", 0}}},
         {"mode", 0},
         {"extensions",
          {{"KHR_gaussian_splatting",
            {{"kernel", "ellipse"}, {"colorSpace", "srgb_rec709_display"}, {"extensions", spz_ext}}}}}});
    const SplatCloud out = splat_lod::read_gltf_splats(span_of(b.file()), "spz.gltf");
    ASSERT_EQ(out.size(), want.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        EXPECT_EQ(out.positions[i], glm::vec3(-want.positions[i].x, want.positions[i].y, -want.positions[i].z));
        EXPECT_EQ(out.rotations[i].w, want.rotations[i].w);
        EXPECT_EQ(out.rotations[i].x, -want.rotations[i].x);
        EXPECT_EQ(out.rotations[i].y, want.rotations[i].y);
        EXPECT_EQ(out.rotations[i].z, -want.rotations[i].z);
        EXPECT_EQ(out.log_scales[i], want.log_scales[i]);
        EXPECT_EQ(out.sh_dc[i], want.sh_dc[i]);
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(out.sh_rest_at(i, 1, c), want.sh_rest_at(i, 1, c));   // y
            EXPECT_EQ(out.sh_rest_at(i, 2, c), -want.sh_rest_at(i, 2, c));  // z
            EXPECT_EQ(out.sh_rest_at(i, 3, c), -want.sh_rest_at(i, 3, c));  // x
        }
    }
}

// tests/data/gltf_splats/two_quantised.gltf, written by hand: signed-byte rotations, unsigned-byte scales
// and opacities (normalized), under a node translated by (10, 0, 0) and scaled by 2.
TEST(GltfSplats, HandWrittenQuantisedFileReadsAsItsValues) {
    ENGINE_REQUIRE_DATA("gltf_splats/two_quantised.gltf");
    splat_lod::LoadReport report;
    const SplatCloud c = splat_lod::load_splat_file(engine::test::data_file("gltf_splats/two_quantised.gltf"), &report);
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c.positions[0], glm::vec3(10, 0, 0));
    EXPECT_EQ(c.positions[1], glm::vec3(12, 4, 6));
    EXPECT_FLOAT_EQ(c.rotations[0].w, 1.0f);
    EXPECT_FLOAT_EQ(c.rotations[1].x, 1.0f);  // (x, y, z, w) = (1, 0, 0, 0): a half turn about x
    EXPECT_NEAR(c.log_scales[0].x, std::log(2.0), 1e-6);
    EXPECT_NEAR(c.log_scales[0].y, std::log(2.0 * 51 / 255), 1e-6);
    EXPECT_NEAR(c.log_scales[0].z, std::log(2.0 * 102 / 255), 1e-6);
    EXPECT_NEAR(c.log_scales[1].z, std::log(2.0), 1e-6);
    EXPECT_FLOAT_EQ(c.opacity_logits[0], splat_lod::opacity_to_logit(1.0f));
    EXPECT_FLOAT_EQ(c.opacity_logits[1], splat_lod::opacity_to_logit(128.0f / 255.0f));
    EXPECT_EQ(c.sh_dc[0], glm::vec3(0.5f, -0.5f, 1.0f));
    EXPECT_TRUE(report.warnings.empty());  // a uniform scale does not rotate: no SH warning
}

// A .gltf with its buffer in a file beside it reads; one whose buffer lies outside its folder does not.
TEST(GltfSplats, ExternalBuffersOnlyFromTheFilesFolder) {
    const auto dir = engine::test::output_dir("gltf_splats") / "external";
    std::filesystem::create_directories(dir / "inner");
    const SplatCloud cloud = make_cloud(6, 1, 30);
    auto doc = nlohmann::json::parse(splat_lod::encode_gltf_splats(cloud, false));
    // The buffer's bytes: the .glb's BIN chunk (after the 12-byte header and the JSON chunk).
    const auto glb = splat_lod::encode_gltf_splats(cloud, true);
    const std::uint32_t json_length =
        glb[12] | glb[13] << 8 | glb[14] << 16 | static_cast<std::uint32_t>(glb[15]) << 24;
    const std::vector<std::uint8_t> bin(glb.begin() + 28 + json_length, glb.end());
    engine::write_file_atomic(dir / "inner" / "splats.bin", bin);
    engine::write_file_atomic(dir / "outside.bin", bin);
    doc["buffers"][0]["uri"] = "splats.bin";
    engine::write_text_file_atomic(dir / "inner" / "a.gltf", doc.dump());
    const SplatCloud back = splat_lod::read_gltf_splats(dir / "inner" / "a.gltf");
    EXPECT_EQ(back.positions, cloud.positions);
    doc["buffers"][0]["uri"] = "../outside.bin";
    engine::write_text_file_atomic(dir / "inner" / "b.gltf", doc.dump());
    const std::string message = splat_io_test::error_of([&] { splat_lod::read_gltf_splats(dir / "inner" / "b.gltf"); });
    EXPECT_NE(message.find("b.gltf: cannot load glTF"), std::string::npos) << message;
}

}  // namespace
