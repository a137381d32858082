#pragma once
// The CPU copy of a Gaussian splat scene as a structure of arrays, in the stored (not activated)
// parameterisation of 3DGS (docs/algorithms.md §1): log-scales, opacity logits, SH coefficients.
// Every reader returns one of these after sanitise(); every writer takes one.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "splat_lod/msgs/level_handover.h"

namespace splat_lod {

// Unit quaternion in the INRIA PLY order rot_0..rot_3 = (w, x, y, z). A named struct rather than
// glm::quat so that the component order can never be mistaken.
struct Rotation {
    float w = 1.0f;
    float x = 0.0f;
    float y = 0.0f;
    float z = 0.0f;
};

// A per-Gaussian float attribute that the engine does not interpret but keeps, so that a
// PLY read and written back loses nothing (e.g. "filter_3D" from Mip-Splatting).
struct ExtraProperty {
    std::string name;
    std::vector<float> values;
};

// What a reader did besides returning the Gaussians: the format it recognised, how many Gaussians
// the file held and how many were dropped (and why), and non-fatal oddities.
struct LoadReport {
    std::string format;
    std::size_t gaussians_in_file = 0;
    std::size_t loaded = 0;
    std::size_t dropped_non_finite = 0;     // NaN or Inf in any attribute
    std::size_t dropped_zero_rotation = 0;  // quaternion of (near) zero length
    std::vector<std::string> warnings;
    // The file says the scene was trained with the 2D mip (anti-aliasing) filter (SPZ flag 0x1),
    // so it should be drawn with that filter on.
    bool antialiased = false;

    std::size_t dropped() const { return dropped_non_finite + dropped_zero_rotation; }
};

constexpr int kMaxShDegree = 3;
constexpr float kShC0 = 0.28209479177387814f;  // Y_0^0, the DC basis value

// Number of SH coefficients per channel beyond DC: 0, 3, 8, 15 for degree 0..3.
constexpr int sh_rest_coeffs(int degree) {
    return (degree + 1) * (degree + 1) - 1;
}

// How a baked cloud's levels hand over (plugin_msgs::LevelHandover, where its kinds are defined), which
// decides where its fades lie under the transition placement `auto`. Kept in a baked PLY's header and
// a glTF splat primitive's extras (splat_io.h).
using LevelHandover = plugin_msgs::LevelHandover;
const char* level_handover_name(LevelHandover handover);
std::optional<LevelHandover> parse_level_handover(const std::string& name);
// The PLY header comment that carries it: "comment splat_lod level_handover <name>".
inline constexpr const char* kLevelHandoverComment = "splat_lod level_handover";

struct SplatCloud {
    std::vector<glm::vec3> positions;
    std::vector<Rotation> rotations;
    std::vector<glm::vec3> log_scales;
    std::vector<float> opacity_logits;
    std::vector<glm::vec3> sh_dc;  // (R, G, B) DC coefficients, INRIA f_dc_0..2

    // Higher-order SH, sh_rest_stride() floats per Gaussian, coefficient-major and channel-minor:
    // sh_rest[i * stride + (k - 1) * 3 + c] holds coefficient k (1..15, the 3DGS basis order) of
    // channel c (0 = R, 1 = G, 2 = B). This is one vec3 per coefficient, the order a shader reads;
    // INRIA's f_rest is channel-major (f_rest_{c*K + k-1}) and the readers transpose it.
    std::vector<float> sh_rest;
    int sh_degree = 0;

    // LOD attributes: the level a Gaussian belongs to (1 = original) and the pixel-coverage range
    // in which it is drawn; -1 means unset.
    std::vector<std::uint8_t> lod_level;
    std::vector<float> coverage_min;
    std::vector<float> coverage_max;
    LevelHandover level_handover = LevelHandover::unknown;

    std::vector<ExtraProperty> extras;

    std::size_t size() const { return positions.size(); }
    bool empty() const { return positions.empty(); }
    std::size_t sh_rest_stride() const { return static_cast<std::size_t>(3 * sh_rest_coeffs(sh_degree)); }

    // coeff is 1..sh_rest_coeffs(sh_degree), channel 0..2.
    float& sh_rest_at(std::size_t i, int coeff, int channel);
    float sh_rest_at(std::size_t i, int coeff, int channel) const;

    // Resizes every array; new Gaussians get identity rotation, zero SH, level 1, unset coverage.
    void resize(std::size_t n);
    // Changes the SH degree, keeping the common coefficients and zero-filling new ones.
    void set_sh_degree(int degree);
    // True when any Gaussian has a level other than 1 or a set coverage bound.
    bool has_lod_attributes() const;

    ExtraProperty* find_extra(const std::string& name);
    const ExtraProperty* find_extra(const std::string& name) const;
    ExtraProperty& add_extra(const std::string& name);  // zero-filled, size() values

    // Throws engine::Error when the arrays disagree in length (a programming error, not bad input).
    void check_consistent() const;

    // Keeps the Gaussians whose flag is non-zero, in order. keep.size() must equal size().
    void keep_only(const std::vector<std::uint8_t>& keep);
    // The Gaussians in `order` (indices into this cloud; every array, SH rest and extras included).
    // Throws engine::Error for an index out of range.
    SplatCloud permuted(const std::vector<std::uint32_t>& order) const;
};

// Appends `part` to `into` (a capture read in pieces): the result has the higher of the two SH degrees
// (missing coefficients zero), keeps only the extra properties both have (by name), and its level
// handover becomes unknown where the two differ. An empty `into` without extras simply becomes `part`.
void append_cloud(SplatCloud& into, SplatCloud&& part);

// Drops every Gaussian with a NaN or Inf in any attribute or a zero quaternion, normalises the
// remaining quaternions, and records the counts in report (if given). Returns the number dropped.
std::size_t sanitise(SplatCloud& cloud, LoadReport* report);

}  // namespace splat_lod
