// One KHR_gaussian_splatting primitive to Gaussians: accessors decoded with the glTF rules for
// normalised integers, every attribute checked for its accessor type, component type and count.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <vector>

#include "gltf_splats.h"
#include "io_util.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod::io {
namespace {

// A component type with its normalized flag, as the spec's attribute table lists them.
struct Encoding {
    int component;
    bool normalized;
};
constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;

const std::vector<Encoding> kFloatOnly = {{kFloat, false}};
const std::vector<Encoding> kPositionEncodings = {{kFloat, false}, {kByte, false},   {kByte, true},
                                                  {kUByte, false}, {kUByte, true},   {kShort, false},
                                                  {kShort, true},  {kUShort, false}, {kUShort, true}};
const std::vector<Encoding> kRotationEncodings = {{kFloat, false}, {kByte, true}, {kShort, true}};
const std::vector<Encoding> kScaleEncodings = {
    {kFloat, false}, {kUByte, false}, {kUByte, true}, {kUShort, false}, {kUShort, true}};
const std::vector<Encoding> kUnitEncodings = {{kFloat, false}, {kUByte, true}, {kUShort, true}};
const std::vector<Encoding> kLevelEncodings = {{kUByte, false}};

std::string type_name(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        default:
            return "type " + std::to_string(type);
    }
}

std::string encoding_name(int component, bool normalized) {
    std::string name;
    switch (component) {
        case kFloat:
            name = "float";
            break;
        case kByte:
            name = "signed byte";
            break;
        case kUByte:
            name = "unsigned byte";
            break;
        case kShort:
            name = "signed short";
            break;
        case kUShort:
            name = "unsigned short";
            break;
        default:
            name = "component type " + std::to_string(component);
    }
    return normalized ? name + " normalized" : name;
}

float decode_component(const std::uint8_t* p, int component, bool normalized) {
    switch (component) {
        case kUByte:
            return normalized ? static_cast<float>(*p) / 255.0f : static_cast<float>(*p);
        case kByte: {
            const auto v = static_cast<float>(static_cast<std::int8_t>(*p));
            return normalized ? std::max(v / 127.0f, -1.0f) : v;
        }
        case kUShort: {
            std::uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? static_cast<float>(v) / 65535.0f : static_cast<float>(v);
        }
        case kShort: {
            std::int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(static_cast<float>(v) / 32767.0f, -1.0f) : static_cast<float>(v);
        }
        default:
            return load_f32le(p);
    }
}

struct AttributeReader {
    const tinygltf::Model& model;
    const std::string& where;

    [[noreturn]] void error(const std::string& attribute, const std::string& what) const {
        engine::fail(where + ": " + attribute + ": " + what);
    }

    // Checks the accessor and returns its bytes' base offset and stride.
    std::pair<std::size_t, std::size_t> locate(const tinygltf::Accessor& a, const std::string& attribute,
                                               std::size_t element) const {
        if (a.sparse.isSparse) error(attribute, "sparse accessors are not supported");
        if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
            error(attribute, "accessor without a valid buffer view");
        const auto& view = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
        if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
            error(attribute, "buffer index out of range");
        const std::size_t size = model.buffers[static_cast<std::size_t>(view.buffer)].data.size();
        if (view.byteOffset > size || view.byteLength > size - view.byteOffset)
            error(attribute, "buffer view exceeds its buffer (truncated file?)");
        const std::size_t stride = view.byteStride != 0 ? view.byteStride : element;
        if (stride < element) error(attribute, "byte stride smaller than an element");
        if (a.count > 0) {
            if (a.count > (std::numeric_limits<std::size_t>::max() - element) / stride ||
                a.byteOffset > view.byteLength || (a.count - 1) * stride + element > view.byteLength - a.byteOffset)
                error(attribute, std::to_string(a.count) + " elements exceed the buffer view");
        }
        return {view.byteOffset + a.byteOffset, stride};
    }

    // `components` floats per element, after checking the accessor type and encoding.
    std::vector<float> read(int index, const std::string& attribute, int type,
                            const std::vector<Encoding>& allowed) const {
        if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
            error(attribute, "accessor index out of range");
        const auto& a = model.accessors[static_cast<std::size_t>(index)];
        if (a.type != type) error(attribute, "accessor type " + type_name(a.type) + ", expected " + type_name(type));
        const bool ok = std::any_of(allowed.begin(), allowed.end(), [&](const Encoding& e) {
            return e.component == a.componentType && e.normalized == a.normalized;
        });
        if (!ok) error(attribute, "component type " + encoding_name(a.componentType, a.normalized) + " is not allowed");
        const auto components =
            static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type)));
        const auto size =
            static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
        const auto [base, stride] = locate(a, attribute, components * size);
        const auto& view = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
        const std::uint8_t* bytes = model.buffers[static_cast<std::size_t>(view.buffer)].data.data() + base;
        std::vector<float> values(a.count * components);
        for (std::size_t i = 0; i < a.count; ++i)
            for (std::size_t c = 0; c < components; ++c)
                values[i * components + c] =
                    decode_component(bytes + i * stride + c * size, a.componentType, a.normalized);
        return values;
    }
};

// The SH degree that the primitive's attributes fully define, or an error for partial or unknown ones.
int sh_degree_of(const std::map<std::string, int>& attributes, const std::string& where) {
    int degree = 0;
    for (const auto& [name, index] : attributes) {
        if (name.rfind(kAttrPrefix + "SH_DEGREE_", 0) != 0) continue;
        int l = -1, n = -1;
        char tail = 0;
        const std::string rest = name.substr(kAttrPrefix.size());
        if (std::sscanf(rest.c_str(), "SH_DEGREE_%d_COEF_%d%c", &l, &n, &tail) != 2 || l < 0 || n < 0 || n > 2 * l ||
            sh_attribute(l, n) != name)
            engine::fail(where + ": " + name + ": not a spherical harmonics attribute name");
        if (l > kMaxShDegree)
            engine::fail(where + ": " + name + ": SH degree " + std::to_string(l) + " is not supported (0 to 3)");
        degree = std::max(degree, l);
    }
    for (int l = 1; l <= degree; ++l)
        for (int n = 0; n <= 2 * l; ++n)
            if (!attributes.count(sh_attribute(l, n)))
                engine::fail(where + ": SH degree " + std::to_string(degree) +
                             " is partially defined: " + sh_attribute(l, n) + " is missing");
    return degree;
}

struct PrimitiveDecoder {
    const tinygltf::Model& model;
    const std::map<std::string, int>& attributes;
    std::string where;  // "<file>: mesh M primitive P"
    std::string label;  // "mesh M primitive P"
    LoadReport& report;
    std::size_t count = 0;

    std::vector<float> read(const std::string& name, int type, const std::vector<Encoding>& allowed) const {
        const auto it = attributes.find(name);
        if (it == attributes.end()) engine::fail(where + ": missing required attribute " + name);
        const auto values = AttributeReader{model, where}.read(it->second, name, type, allowed);
        const auto components =
            static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type)));
        if (values.size() / components != count)
            engine::fail(where + ": " + name + ": " + std::to_string(values.size() / components) +
                         " elements, but POSITION has " + std::to_string(count));
        return values;
    }
    bool quantised(const std::string& name) const {
        return model.accessors[static_cast<std::size_t>(attributes.at(name))].componentType != kFloat;
    }
    void warn(std::size_t n, const std::string& what) const {
        if (n > 0) report.warnings.push_back(label + ": " + std::to_string(n) + " " + what);
    }
};

void decode_rotations(const PrimitiveDecoder& d, SplatCloud& cloud) {
    const auto q = d.read(kAttrRotation, TINYGLTF_TYPE_VEC4, kRotationEncodings);
    // Quantised quaternions miss unit length by up to about one step per component.
    const double tolerance = d.quantised(kAttrRotation) ? 0.03 : 1e-3;
    std::size_t off = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Rotation r{q[4 * i + 3], q[4 * i], q[4 * i + 1], q[4 * i + 2]};  // glTF order: x, y, z, w
        const double len = std::sqrt(double(r.w) * r.w + double(r.x) * r.x + double(r.y) * r.y + double(r.z) * r.z);
        if (std::abs(len - 1.0) > tolerance && len > 0.0) ++off;
        cloud.rotations[i] = r;
    }
    d.warn(off, "rotations are not unit quaternions (normalised)");
}

void decode_scales_and_opacity(const PrimitiveDecoder& d, SplatCloud& cloud) {
    const auto s = d.read(kAttrScale, TINYGLTF_TYPE_VEC3, kScaleEncodings);
    std::size_t negative = 0, tiny = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            float v = s[3 * i + static_cast<std::size_t>(c)];
            if (v < 0.0f) ++negative, v = -v;
            if (v < kGltfMinScale) ++tiny, v = kGltfMinScale;
            cloud.log_scales[i][c] = static_cast<float>(std::log(static_cast<double>(v)));
        }
    d.warn(negative, "negative scale values (their absolute value is used)");
    d.warn(tiny, "scale values below 1e-12 (raised to 1e-12)");
    const auto o = d.read(kAttrOpacity, TINYGLTF_TYPE_SCALAR, kUnitEncodings);
    std::size_t clamped = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        float v = o[i];
        if (v < 0.0f || v > 1.0f) ++clamped, v = std::clamp(v, 0.0f, 1.0f);
        cloud.opacity_logits[i] = opacity_to_logit(v);
    }
    d.warn(clamped, "opacities outside [0, 1] (clamped)");
}

float linear_to_srgb(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

// DC from SH_DEGREE_0_COEF_0, or from the fallback COLOR_0 (linear, so sRGB-encoded first when the
// colour space is sRGB), then the higher degrees.
void decode_colour(const PrimitiveDecoder& d, SplatCloud& cloud, bool srgb) {
    if (d.attributes.count(sh_attribute(0, 0))) {
        const auto dc = d.read(sh_attribute(0, 0), TINYGLTF_TYPE_VEC3, kFloatOnly);
        for (std::size_t i = 0; i < cloud.size(); ++i) cloud.sh_dc[i] = {dc[3 * i], dc[3 * i + 1], dc[3 * i + 2]};
    } else {
        const int index = d.attributes.at("COLOR_0");
        const bool vec4 = index >= 0 && static_cast<std::size_t>(index) < d.model.accessors.size() &&
                          d.model.accessors[static_cast<std::size_t>(index)].type == TINYGLTF_TYPE_VEC4;
        const std::size_t n = vec4 ? 4 : 3;
        const auto rgb = d.read("COLOR_0", vec4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, kUnitEncodings);
        for (std::size_t i = 0; i < cloud.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const float v = rgb[n * i + static_cast<std::size_t>(c)];
                cloud.sh_dc[i][c] = ((srgb ? linear_to_srgb(v) : v) - 0.5f) / kShC0;
            }
        d.report.warnings.push_back(d.label + ": no " + sh_attribute(0, 0) + "; the colour comes from COLOR_0");
    }
    for (int l = 1; l <= cloud.sh_degree; ++l)
        for (int n = 0; n <= 2 * l; ++n) {
            const auto v = d.read(sh_attribute(l, n), TINYGLTF_TYPE_VEC3, kFloatOnly);
            for (std::size_t i = 0; i < cloud.size(); ++i)
                for (int c = 0; c < 3; ++c) cloud.sh_rest_at(i, l * l + n, c) = v[3 * i + static_cast<std::size_t>(c)];
        }
}

// The project's own attributes: LOD level and coverage range, and extra properties (in the order of
// their accessors, which is the order the writer keeps them in).
void decode_lod_attributes(const PrimitiveDecoder& d, SplatCloud& cloud) {
    std::vector<std::pair<int, std::string>> extras;
    for (const auto& [name, index] : d.attributes) {
        if (name.rfind(kLodPrefix, 0) != 0) continue;
        if (name == kAttrLodLevel) {
            const auto v = d.read(name, TINYGLTF_TYPE_SCALAR, kLevelEncodings);
            for (std::size_t i = 0; i < cloud.size(); ++i) cloud.lod_level[i] = static_cast<std::uint8_t>(v[i]);
        } else if (name == kAttrCoverageMin || name == kAttrCoverageMax) {
            const auto v = d.read(name, TINYGLTF_TYPE_SCALAR, kFloatOnly);
            (name == kAttrCoverageMin ? cloud.coverage_min : cloud.coverage_max).assign(v.begin(), v.end());
        } else if (name.rfind(kAttrExtraPrefix, 0) == 0 && name.size() > kAttrExtraPrefix.size()) {
            extras.emplace_back(index, name);
        } else {
            d.report.warnings.push_back(d.label + ": unknown attribute " + name + " ignored");
        }
    }
    std::sort(extras.begin(), extras.end());
    for (const auto& [index, name] : extras)
        cloud.add_extra(name.substr(kAttrExtraPrefix.size())).values = d.read(name, TINYGLTF_TYPE_SCALAR, kFloatOnly);
}

// The level handover a baked cloud's writer leaves in the primitive's extras (kExtrasLevelHandover).
void decode_level_handover(const tinygltf::Primitive& primitive, const PrimitiveDecoder& d, SplatCloud& cloud) {
    if (!primitive.extras.IsObject() || !primitive.extras.Has(kExtrasLevelHandover)) return;
    const tinygltf::Value& value = primitive.extras.Get(kExtrasLevelHandover);
    const std::string name = value.IsString() ? value.Get<std::string>() : std::string("(not a string)");
    if (const auto handover = parse_level_handover(name))
        cloud.level_handover = *handover;
    else
        d.report.warnings.push_back(d.label + ": unknown level handover \"" + name +
                                    "\" in its extras, read as unknown");
}

// The extension object: unknown kernels and the linear colour space are warned about.
struct ExtensionInfo {
    bool srgb = true;
    int spz_view = -1;  // the buffer view of KHR_gaussian_splatting_compression_spz_2, or -1
};
ExtensionInfo check_extension(const tinygltf::Primitive& primitive, const PrimitiveDecoder& d) {
    const tinygltf::Value& ext = primitive.extensions.at(kGltfSplatExtension);
    if (!ext.IsObject())
        engine::fail(d.where + ": the " + std::string(kGltfSplatExtension) + " value is not an object");
    ExtensionInfo info;
    const tinygltf::Value& nested = ext.Get("extensions");
    if (nested.IsObject() && nested.Has(kGltfSpzExtension)) {
        const tinygltf::Value& view = nested.Get(kGltfSpzExtension).Get("bufferView");
        if (!view.IsInt() || view.Get<int>() < 0)
            engine::fail(d.where + ": " + kGltfSpzExtension + " without a valid bufferView");
        info.spz_view = view.Get<int>();
    }
    const tinygltf::Value& kernel = ext.Get("kernel");
    if (kernel.IsString() && kernel.Get<std::string>() != "ellipse")
        d.report.warnings.push_back(d.label + ": kernel \"" + kernel.Get<std::string>() + "\" drawn as \"ellipse\"");
    const tinygltf::Value& space = ext.Get("colorSpace");
    info.srgb = !(space.IsString() && space.Get<std::string>() == "lin_rec709_display");
    if (!info.srgb)
        d.report.warnings.push_back(d.label + ": colorSpace lin_rec709_display: colours are drawn unconverted");
    return info;
}

}  // namespace

std::string sh_attribute(int degree, int coef) {
    return kAttrPrefix + "SH_DEGREE_" + std::to_string(degree) + "_COEF_" + std::to_string(coef);
}

SplatCloud decode_splat_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                  const std::string& name, const std::string& label, LoadReport& report) {
    PrimitiveDecoder d{model, primitive.attributes, name + ": " + label, label, report};
    if (primitive.mode != TINYGLTF_MODE_POINTS)
        engine::fail(d.where + ": mode " + std::to_string(primitive.mode) + "; " + kGltfSplatExtension +
                     " needs POINTS (0)");
    const ExtensionInfo info = check_extension(primitive, d);
    if (info.spz_view >= 0) return decode_spz_primitive(model, primitive, info.spz_view, d.where, report);
    for (const std::string& required : {std::string("POSITION"), kAttrRotation, kAttrScale, kAttrOpacity})
        if (!d.attributes.count(required)) engine::fail(d.where + ": missing required attribute " + required);
    if (!d.attributes.count(sh_attribute(0, 0)) && !d.attributes.count("COLOR_0"))
        engine::fail(d.where + ": missing required attribute " + sh_attribute(0, 0) + " (and no COLOR_0)");
    const int degree = sh_degree_of(d.attributes, d.where);
    if (degree > 0 && !d.attributes.count(sh_attribute(0, 0)))
        engine::fail(d.where + ": SH degree " + std::to_string(degree) + " without " + sh_attribute(0, 0));
    const auto positions = AttributeReader{model, d.where}.read(d.attributes.at("POSITION"), "POSITION",
                                                                TINYGLTF_TYPE_VEC3, kPositionEncodings);
    d.count = positions.size() / 3;
    SplatCloud cloud;
    cloud.set_sh_degree(degree);
    cloud.resize(d.count);
    for (std::size_t i = 0; i < d.count; ++i)
        cloud.positions[i] = {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
    decode_rotations(d, cloud);
    decode_scales_and_opacity(d, cloud);
    decode_colour(d, cloud, info.srgb);
    decode_lod_attributes(d, cloud);
    decode_level_handover(primitive, d, cloud);
    return cloud;
}

}  // namespace splat_lod::io
