// KHR_gaussian_splatting files that break the rules: each refused with an error naming the file, the
// primitive and the problem; what the spec leaves undefined is read with a documented choice and a
// warning. The files are built here from a valid one with one edit each.
#include <gtest/gtest.h>

#include "gltf_splats_test_helpers.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"

using gltf_test::Builder;
using splat_io_test::error_of;
using splat_io_test::make_cloud;

namespace {

const std::string kPrefix = "KHR_gaussian_splatting:";

Builder valid(int degree = 0) {
    Builder b;
    b.primitive(make_cloud(8, degree, 4));
    return b;
}

std::string error_reading(Builder& b) {
    const auto bytes = b.file();
    return error_of([&] { splat_lod::read_gltf_splats(std::span<const std::uint8_t>(bytes), "bad.gltf"); });
}

void expect_error(Builder& b, const std::string& problem) {
    const std::string message = error_reading(b);
    EXPECT_EQ(message.rfind("bad.gltf: ", 0), 0u) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
}

splat_lod::LoadReport report_of(Builder& b, splat_lod::SplatCloud* out = nullptr) {
    splat_lod::LoadReport report;
    const auto bytes = b.file();
    auto cloud = splat_lod::read_gltf_splats(std::span<const std::uint8_t>(bytes), "odd.gltf", &report);
    if (out) *out = std::move(cloud);
    return report;
}

bool has_warning(const splat_lod::LoadReport& r, const std::string& text) {
    for (const auto& w : r.warnings)
        if (w.find(text) != std::string::npos) return true;
    return false;
}

TEST(GltfSplatsHostile, WrongAccessorType) {
    Builder b = valid();
    b.doc["accessors"][b.prim()["attributes"][kPrefix + "SCALE"].get<int>()]["type"] = "VEC4";
    expect_error(b, "mesh 0 primitive 0: KHR_gaussian_splatting:SCALE: accessor type VEC4, expected VEC3");
}

TEST(GltfSplatsHostile, WrongComponentType) {
    Builder b = valid();
    auto& a = b.doc["accessors"][b.prim()["attributes"][kPrefix + "ROTATION"].get<int>()];
    a["componentType"] = gltf_test::kUByte;  // rotations may be signed byte normalized, not unsigned
    a["normalized"] = true;
    expect_error(
        b,
        "mesh 0 primitive 0: KHR_gaussian_splatting:ROTATION: component type unsigned byte normalized is not allowed");
}

TEST(GltfSplatsHostile, AttributeCountsDiffer) {
    Builder b = valid();
    b.doc["accessors"][b.prim()["attributes"][kPrefix + "OPACITY"].get<int>()]["count"] = 7;
    expect_error(b, "mesh 0 primitive 0: KHR_gaussian_splatting:OPACITY: 7 elements, but POSITION has 8");
}

TEST(GltfSplatsHostile, MissingRequiredAttribute) {
    Builder b = valid();
    b.prim()["attributes"].erase(kPrefix + "ROTATION");
    expect_error(b, "mesh 0 primitive 0: missing required attribute KHR_gaussian_splatting:ROTATION");
}

TEST(GltfSplatsHostile, PartiallyDefinedShDegree) {
    Builder b = valid(2);
    b.prim()["attributes"].erase(kPrefix + "SH_DEGREE_2_COEF_3");
    expect_error(
        b,
        "mesh 0 primitive 0: SH degree 2 is partially defined: KHR_gaussian_splatting:SH_DEGREE_2_COEF_3 is missing");
    Builder c = valid(1);
    c.prim()["attributes"][kPrefix + "SH_DEGREE_4_COEF_0"] = 0;
    expect_error(c, "SH degree 4 is not supported");
}

TEST(GltfSplatsHostile, ModeNotPoints) {
    Builder b = valid();
    b.prim()["mode"] = 4;
    expect_error(b, "mesh 0 primitive 0: mode 4; KHR_gaussian_splatting needs POINTS (0)");
    b.prim().erase("mode");  // the glTF default is TRIANGLES
    expect_error(b, "mode 4");
}

TEST(GltfSplatsHostile, NonDecomposableNodeMatrices) {
    Builder shear = valid();
    shear.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    expect_error(shear, "node 0 (mesh 0 primitive 0): the transform is not decomposable (it shears)");
    Builder zero = valid();
    zero.doc["nodes"][0]["scale"] = {1, 0, 1};
    expect_error(zero, "node 0 (mesh 0 primitive 0): the transform is not decomposable (zero or non-finite scale)");
}

TEST(GltfSplatsHostile, NoSplatPrimitive) {
    Builder b = valid();
    b.prim().erase("extensions");
    expect_error(b, "no KHR_gaussian_splatting primitive");
}

// An SPZ-compressed primitive whose stream holds another count than its POSITION accessor, and one whose
// buffer view is not there.
TEST(GltfSplatsHostile, SpzCompressedWithWrongCountOrView) {
    Builder b = valid();
    b.prim()["extensions"]["KHR_gaussian_splatting"]["extensions"] = {
        {"KHR_gaussian_splatting_compression_spz_2", {{"bufferView", 0}}}};
    expect_error(b, "mesh 0 primitive 0: KHR_gaussian_splatting_compression_spz_2: ");  // not an SPZ stream
    b.prim()["extensions"]["KHR_gaussian_splatting"]["extensions"]["KHR_gaussian_splatting_compression_spz_2"]
            ["bufferView"] = 99;
    expect_error(b, "mesh 0 primitive 0: KHR_gaussian_splatting_compression_spz_2: bufferView out of range");
}

TEST(GltfSplatsHostile, AccessorBeyondItsBuffer) {
    Builder b = valid();
    b.doc["accessors"][0]["count"] = 1000000;
    const std::string message = error_reading(b);
    EXPECT_EQ(message.rfind("bad.gltf: ", 0), 0u) << message;
}

// Undefined by the spec: quaternions not of unit length are normalised, negative scales taken by
// absolute value, opacities clamped to [0, 1]; each with a warning naming the primitive.
TEST(GltfSplatsHostile, UndefinedValuesAreReadWithWarnings) {
    splat_lod::SplatCloud cloud = make_cloud(4, 0, 9);
    cloud.rotations[0] = {2.0f, 0.0f, 0.0f, 0.0f};
    Builder b;
    b.primitive(cloud);
    auto values = [&](const std::string& attribute) {
        const int accessor = b.prim()["attributes"][attribute].get<int>();
        const int view = b.doc["accessors"][accessor]["bufferView"].get<int>();
        return reinterpret_cast<float*>(b.bytes.data() + b.doc["bufferViews"][view]["byteOffset"].get<std::size_t>());
    };
    values(kPrefix + "SCALE")[3] = -0.25f;  // Gaussian 1, x
    values(kPrefix + "OPACITY")[2] = 1.5f;
    splat_lod::SplatCloud out;
    const auto report = report_of(b, &out);
    EXPECT_TRUE(has_warning(report, "mesh 0 primitive 0: 1 rotations are not unit quaternions (normalised)"));
    EXPECT_TRUE(has_warning(report, "mesh 0 primitive 0: 1 negative scale values (their absolute value is used)"));
    EXPECT_TRUE(has_warning(report, "mesh 0 primitive 0: 1 opacities outside [0, 1] (clamped)"));
    ASSERT_EQ(out.size(), 4u);
    EXPECT_FLOAT_EQ(out.rotations[0].w, 1.0f);
    EXPECT_NEAR(out.log_scales[1].x, std::log(0.25f), 1e-6);
    EXPECT_FLOAT_EQ(out.opacity_logits[2], splat_lod::opacity_to_logit(1.0f));
}

TEST(GltfSplatsHostile, NotGltfAtAll) {
    const std::string text = "{\"asset\": ";
    const std::vector<std::uint8_t> bytes(text.begin(), text.end());
    const std::string message =
        error_of([&] { splat_lod::read_gltf_splats(std::span<const std::uint8_t>(bytes), "bad.gltf"); });
    EXPECT_EQ(message.rfind("bad.gltf: cannot load glTF", 0), 0u) << message;
}

}  // namespace
