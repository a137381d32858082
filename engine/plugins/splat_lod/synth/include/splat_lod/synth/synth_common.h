#pragma once
// Private helpers of the synth builders: platform-independent sine, cosine and logarithm, local
// frames as quaternions, smooth value noise, argument checks, and the one function that appends
// a Gaussian to a SplatCloud in the stored parameterisation.
//
// Include this header first in every synth source: the pragmas below must precede every
// function the generator compiles, glm's and the standard library's inline ones included.
// Fusing a·b + c into one rounding (FMA) is the compilers' default on targets that have it
// (AArch64, x86-64 with -march=haswell or later) and would change the output's low bits between
// platforms; switched off, every IEEE 754 platform computes the same bytes.
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include <string>

#include <glm/glm.hpp>

#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/synth/fine_detail_scene.h"

namespace splat_lod::synth {

constexpr double kPi = 3.14159265358979323846;
constexpr float kTwoPiF = 6.28318530717958647692f;

// Sine and cosine from range reduction and Taylor polynomials (|error| < 1e-15 for |x| < 1e3),
// used instead of std::sin/std::cos because standard libraries round those differently.
struct SinCos {
    float sin = 0.0f;
    float cos = 1.0f;
};
SinCos sin_cos(double angle);
// Natural logarithm of a positive finite x (same reason as sin_cos).
double log_det(double x);

// A Gaussian before conversion to the stored parameterisation. The axes are orthonormal and
// right-handed (axis_z = axis_x × axis_y); `scale` holds the standard deviations along them.
struct GaussianDraft {
    glm::vec3 position{0.0f};
    glm::vec3 axis_x{1.0f, 0.0f, 0.0f};
    glm::vec3 axis_y{0.0f, 1.0f, 0.0f};
    glm::vec3 scale{0.01f};
    glm::vec3 rgb{0.5f};  // the colour the DC term should give, each channel in [0, 1]
    float opacity_logit = 3.0f;
};

// Appends to every array of the cloud (zero SH rest, level 1, unset coverage, zero extras).
void append_gaussian(SplatCloud& cloud, const GaussianDraft& g);

// Unit quaternion (w, x, y, z) whose matrix has columns axis_x, axis_y, axis_x × axis_y.
Rotation rotation_from_axes(const glm::vec3& axis_x, const glm::vec3& axis_y);

// Every function taking an Rng draws in a fixed order. Callers keep to one draw per expression:
// C++ leaves the evaluation order of operands and function arguments unspecified, so
// f(rng.uniform(), rng.uniform()) could receive its values swapped under another compiler.

// Unit vector uniformly distributed on the sphere (rejection from the cube: no trigonometry).
glm::vec3 random_unit_vector(Rng& rng);
// Any unit vector perpendicular to the unit vector n.
glm::vec3 any_perpendicular(const glm::vec3& n);
// A unit vector perpendicular to the unit vector n at a uniformly random angle.
glm::vec3 random_perpendicular(const glm::vec3& n, Rng& rng);

// Smooth value noise in [0, 1] on a unit lattice (hashing integer corners with the seed),
// for colour patches that vary over metres rather than per Gaussian.
float value_noise(float x, float z, std::uint64_t seed);
float value_noise_3d(const glm::vec3& p, std::uint64_t seed);

glm::vec3 clamp_rgb(const glm::vec3& rgb);
// The scene has no lights; colours carry a fixed sun from the upper left front instead, so that
// crowns, trunks and stones read as volumes rather than flat cut-outs.
inline const glm::vec3 kSunDirection{-0.40f, 0.80f, 0.4472136f};  // unit length
// ambient + (1 − ambient) · max(0, n · sun) for a unit normal.
float sun_shade(const glm::vec3& normal, float ambient);
glm::vec3 mix_rgb(const glm::vec3& a, const glm::vec3& b, float t);

// "%g" formatting for error messages ("0.16", not "0.160000").
std::string number_text(float v);

// Argument checks that throw engine::Error("splat_lod::synth::<builder>(): <what> ...").
void require_finite(const glm::vec3& v, const char* builder, const char* what);
void require_positive(float v, const char* builder, const char* what);
void require_detail(float detail, const char* builder);
// Refuses sizes that would ask for more than kMaxBuilderGaussians (a 50 m tree, a 1 km lawn):
// a mistake in the caller's units, not a scene that fits in memory.
constexpr double kMaxBuilderGaussians = 5e7;
void require_count(double expected_gaussians, const char* builder);

}  // namespace splat_lod::synth
