#pragma once
// Internal pieces of the KHR_gaussian_splatting reader and writer (docs/gltf_splats.md): attribute
// names, the decoding of one splat primitive, node transforms and the merge of primitives into one cloud.
#include <string>

#include <glm/mat4x4.hpp>

#include "splat_lod/core/splat_cloud.h"

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace splat_lod::io {

inline constexpr const char* kGltfSplatExtension = "KHR_gaussian_splatting";
inline constexpr const char* kGltfSpzExtension = "KHR_gaussian_splatting_compression_spz_2";
inline const std::string kAttrPrefix = "KHR_gaussian_splatting:";
inline const std::string kAttrRotation = kAttrPrefix + "ROTATION";
inline const std::string kAttrScale = kAttrPrefix + "SCALE";
inline const std::string kAttrOpacity = kAttrPrefix + "OPACITY";
// The project's own attributes (glTF wants application-specific semantics to start with '_').
inline const std::string kLodPrefix = "_SPLAT_LOD_";
inline const std::string kAttrLodLevel = kLodPrefix + "LEVEL";
inline const std::string kAttrCoverageMin = kLodPrefix + "COVERAGE_MIN";
inline const std::string kAttrCoverageMax = kLodPrefix + "COVERAGE_MAX";
inline const std::string kAttrExtraPrefix = kLodPrefix + "EXTRA_";
// A baked cloud's level handover (SplatCloud::level_handover), a name in the splat primitive's extras.
inline constexpr const char* kExtrasLevelHandover = "splat_lod_level_handover";

// Scales below this (zero in quantised files) are raised to it: its log stays finite.
inline constexpr float kGltfMinScale = 1e-12f;

// "KHR_gaussian_splatting:SH_DEGREE_<degree>_COEF_<coef>"; coefficient k of the cloud (1..15, the 3DGS
// basis order) is degree l = floor(sqrt(k)), coef = k - l*l (the glTF order m = -l..l).
std::string sh_attribute(int degree, int coef);

// The Gaussians of one splat primitive in its mesh's own space. Errors name the file and the
// primitive ("a.glb: mesh 0 primitive 1: ..."); oddities the spec leaves undefined become warnings in
// `report` that name the primitive.
SplatCloud decode_splat_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                  const std::string& name, const std::string& label, LoadReport& report);

// A primitive whose extension holds KHR_gaussian_splatting_compression_spz_2: the SPZ stream in buffer
// view `view`, read by read_spz and turned from SPZ's right-up-back axes into glTF's left-up-front ones
// (x and z negated). The attribute accessors only give the count, which must match.
SplatCloud decode_spz_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, int view,
                                const std::string& where, LoadReport& report);

// Applies a node's world matrix: positions M·p, covariances M·C·Cᵀ·Mᵀ re-decomposed into rotation and
// log-scale. Throws for matrices with shear or a zero or non-finite column; warns for mirrors and, when
// the matrix rotates and the SH degree is 1 or more, that the SH coefficients are not rotated.
void apply_node_transform(SplatCloud& cloud, const glm::dmat4& world, const std::string& name, const std::string& label,
                          LoadReport& report);

// Appends `part` to `cloud`: the higher SH degree of the two, extras matched by name (zero where absent),
// the level handover kept where the parts agree (unknown where they do not).
void append_cloud(SplatCloud& cloud, const SplatCloud& part);

}  // namespace splat_lod::io
