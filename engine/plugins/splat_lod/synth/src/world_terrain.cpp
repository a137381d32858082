// The generated world's ground (world_terrain.h): hills from three octaves of the synth value noise, a
// river valley blended into them, and the path and forest masks. Only +, −, ×, ÷, sqrt, floor and
// the synth sine are used, so the heights are the same bytes everywhere.
#include "splat_lod/synth/synth_common.h"

#include "splat_lod/synth/world_terrain.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "splat_lod/synth/world_streams.h"

namespace splat_lod::world {
namespace {

constexpr double kTwoPi = 2.0 * synth::kPi;

// Hills: wavelengths of the three octaves (metres) and their weights; the height spans ±kHillHeight/2.
constexpr float kHillWavelength[3] = {240.0f, 97.0f, 37.0f};
constexpr float kHillWeight[3] = {0.55f, 0.30f, 0.15f};
constexpr float kHillHeight = 26.0f;

// The river's centre line x(z) = offset + Σ a·F·sin(2π z / (λ·F) + φ), F the feature scale: one wide
// bend across a world of size F and a shorter meander on it.
constexpr float kRiverAmplitude[2] = {0.12f, 0.025f};
constexpr float kRiverWavelength[2] = {0.8f, 0.3f};
constexpr float kPathAmplitude[2] = {0.10f, 0.025f};
constexpr float kPathWavelength[2] = {0.7f, 0.23f};

// The valley: fully carved within kValleyInner of the water's edge, blended back into the hills by
// kValleyOuter; the banks rise 22 cm per metre and the bed is 0.25–0.85 m below the water.
constexpr float kValleyInner = 8.0f;
constexpr float kValleyOuter = 45.0f;
constexpr float kBankSlope = 0.22f;
constexpr float kWaterLevel = -2.5f;
constexpr float kWaterFall = 0.004f;  // metres per metre along +z

float sine(double angle) {
    return synth::sin_cos(angle).sin;
}
float cosine(double angle) {
    return synth::sin_cos(angle).cos;
}

}  // namespace

float WorldTerrain::feature_scale_for(float size_m) {
    return std::min(size_m, kFeatureScaleMax);
}

WorldTerrain::WorldTerrain(std::uint64_t seed, float size_m, float feature_m) : size_(size_m), feature_(feature_m) {
    if (!(std::isfinite(size_m) && size_m > 0.0f))
        engine::fail("splat_lod::world::WorldTerrain: the size must be a positive number of metres");
    if (!(std::isfinite(feature_m) && feature_m > 0.0f && feature_m <= size_m))
        engine::fail(
            "splat_lod::world::WorldTerrain: the feature scale must be a positive number of metres, at most "
            "the size");
    synth::Rng rng(seed, stream_id(StreamKind::terrain, 0, 0));
    for (auto& s : hill_seed_) s = rng.next_u64();
    for (auto& s : forest_seed_) s = rng.next_u64();
    river_.amplitude = kRiverAmplitude;
    river_.wavelength = kRiverWavelength;
    path_.amplitude = kPathAmplitude;
    path_.wavelength = kPathWavelength;
    for (auto& phase : river_.phase) phase = rng.uniform(0.0f, synth::kTwoPiF);
    for (auto& phase : path_.phase) phase = rng.uniform(0.0f, synth::kTwoPiF);
    // Offsets keep both lines well inside the middle square of the feature scale.
    river_.offset = feature_ * rng.uniform(-0.15f, 0.15f);
    path_.offset = feature_ * rng.uniform(-0.2f, 0.2f);
}

float WorldTerrain::hills(float x, float z) const {
    float sum = 0.0f;
    for (int o = 0; o < 3; ++o)
        sum += kHillWeight[o] * synth::value_noise(x / kHillWavelength[o], z / kHillWavelength[o], hill_seed_[o]);
    return kHillHeight * (sum - 0.5f);
}

float WorldTerrain::CentreLine::across(float along, float scale) const {
    float value = offset;
    for (int k = 0; k < 2; ++k)
        value += amplitude[k] * scale * sine(kTwoPi * along / (wavelength[k] * scale) + phase[k]);
    return value;
}

float WorldTerrain::CentreLine::slope(float along, float scale) const {
    float value = 0.0f;
    for (int k = 0; k < 2; ++k)
        value += static_cast<float>(kTwoPi) * amplitude[k] / wavelength[k] *
                 cosine(kTwoPi * along / (wavelength[k] * scale) + phase[k]);
    return value;
}

float WorldTerrain::CentreLine::distance(float across_value, float along, float scale) const {
    const float s = slope(along, scale);
    return std::abs(across_value - across(along, scale)) / std::sqrt(1.0f + s * s);
}

float WorldTerrain::river_x(float z) const {
    return river_.across(z, feature_);
}
float WorldTerrain::river_distance(float x, float z) const {
    return river_.distance(x, z, feature_);
}

float WorldTerrain::water_level(float z) const {
    return kWaterLevel - kWaterFall * z;
}

float WorldTerrain::path_z(float x) const {
    return path_.across(x, feature_);
}
float WorldTerrain::path_distance(float x, float z) const {
    return path_.distance(z, x, feature_);
}

glm::vec2 WorldTerrain::path_direction(float x) const {
    const float slope = path_.slope(x, feature_);
    return glm::vec2(1.0f, slope) / std::sqrt(1.0f + slope * slope);
}

float WorldTerrain::height(float x, float z) const {
    const float base = hills(x, z);
    const float d = river_distance(x, z);
    if (d >= kRiverHalfWidth + kValleyOuter) return base;
    const float water = water_level(z);
    float valley;
    if (d < kRiverHalfWidth) {
        const float across = d / kRiverHalfWidth;
        valley = water - 0.25f - 0.6f * (1.0f - across * across);
    } else {
        valley = water - 0.25f + kBankSlope * (d - kRiverHalfWidth);
    }
    const float carve = 1.0f - glm::smoothstep(kRiverHalfWidth + kValleyInner, kRiverHalfWidth + kValleyOuter, d);
    return base + (valley - base) * carve;
}

glm::vec3 WorldTerrain::normal(float x, float z) const {
    constexpr float e = 0.5f;
    const float dx = height(x + e, z) - height(x - e, z);
    const float dz = height(x, z + e) - height(x, z - e);
    const glm::vec3 n(-dx / (2.0f * e), 1.0f, -dz / (2.0f * e));
    return n / std::sqrt(glm::dot(n, n));
}

float WorldTerrain::forest(float x, float z) const {
    const float noise = 0.7f * synth::value_noise(x / 180.0f, z / 180.0f, forest_seed_[0]) +
                        0.3f * synth::value_noise(x / 50.0f, z / 50.0f, forest_seed_[1]);
    float density = glm::smoothstep(0.5f, 0.64f, noise);
    // Forests thin out towards the water and the path rather than stopping at a wall.
    density *= glm::smoothstep(kRiverHalfWidth + 3.0f, kRiverHalfWidth + 12.0f, river_distance(x, z));
    density *= glm::smoothstep(kPathHalfWidth + 1.5f, kPathHalfWidth + 5.0f, path_distance(x, z));
    return density;
}

}  // namespace splat_lod::world
