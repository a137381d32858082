#include "splat_lod/core/splat_cloud.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/core/error.h"

namespace splat_lod {
namespace {

// Below this squared length a quaternion carries no usable direction (normalising would amplify
// rounding noise into an arbitrary rotation), so the Gaussian is bad input.
// The norm is taken in double so that finite components up to FLT_MAX cannot overflow it.
constexpr double kMinQuaternionNormSquared = 1e-20;

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finite_rotation(const Rotation& r) {
    return std::isfinite(r.w) && std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z);
}

double norm_squared(const Rotation& r) {
    const double w = r.w, x = r.x, y = r.y, z = r.z;
    return w * w + x * x + y * y + z * z;
}

bool finite_gaussian(const SplatCloud& c, std::size_t i) {
    if (!finite3(c.positions[i]) || !finite3(c.log_scales[i]) || !finite3(c.sh_dc[i])) return false;
    if (!finite_rotation(c.rotations[i]) || !std::isfinite(c.opacity_logits[i])) return false;
    if (!std::isfinite(c.coverage_min[i]) || !std::isfinite(c.coverage_max[i])) return false;
    const std::size_t stride = c.sh_rest_stride();
    const float* rest = c.sh_rest.data() + i * stride;
    for (std::size_t k = 0; k < stride; ++k)
        if (!std::isfinite(rest[k])) return false;
    for (const auto& extra : c.extras)
        if (!std::isfinite(extra.values[i])) return false;
    return true;
}

template <typename T>
void compact(std::vector<T>& values, const std::vector<std::uint8_t>& keep, std::size_t stride) {
    std::size_t out = 0;
    for (std::size_t i = 0; i < keep.size(); ++i) {
        if (!keep[i]) continue;
        if (out != i)
            std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(i * stride), stride,
                        values.begin() + static_cast<std::ptrdiff_t>(out * stride));
        ++out;
    }
    values.resize(out * stride);
}

}  // namespace

float& SplatCloud::sh_rest_at(std::size_t i, int coeff, int channel) {
    return sh_rest[i * sh_rest_stride() + static_cast<std::size_t>((coeff - 1) * 3 + channel)];
}

float SplatCloud::sh_rest_at(std::size_t i, int coeff, int channel) const {
    return sh_rest[i * sh_rest_stride() + static_cast<std::size_t>((coeff - 1) * 3 + channel)];
}

void SplatCloud::resize(std::size_t n) {
    positions.resize(n, glm::vec3(0.0f));
    rotations.resize(n);
    log_scales.resize(n, glm::vec3(0.0f));
    opacity_logits.resize(n, 0.0f);
    sh_dc.resize(n, glm::vec3(0.0f));
    sh_rest.resize(n * sh_rest_stride(), 0.0f);
    lod_level.resize(n, 1);
    coverage_min.resize(n, -1.0f);
    coverage_max.resize(n, -1.0f);
    for (auto& extra : extras) extra.values.resize(n, 0.0f);
}

void SplatCloud::set_sh_degree(int degree) {
    if (degree < 0 || degree > kMaxShDegree)
        engine::fail("splat_lod::SplatCloud::set_sh_degree(): degree " + std::to_string(degree) + " is not 0..3");
    const std::size_t old_stride = sh_rest_stride();
    const int old_degree = sh_degree;
    sh_degree = degree;
    const std::size_t new_stride = sh_rest_stride();
    if (old_stride == new_stride) return;
    const std::size_t common = static_cast<std::size_t>(3 * sh_rest_coeffs(std::min(old_degree, degree)));
    std::vector<float> rest(size() * new_stride, 0.0f);
    for (std::size_t i = 0; i < size(); ++i)
        std::copy_n(sh_rest.begin() + static_cast<std::ptrdiff_t>(i * old_stride), common,
                    rest.begin() + static_cast<std::ptrdiff_t>(i * new_stride));
    sh_rest = std::move(rest);
}

bool SplatCloud::has_lod_attributes() const {
    for (std::size_t i = 0; i < size(); ++i)
        if (lod_level[i] != 1 || coverage_min[i] != -1.0f || coverage_max[i] != -1.0f) return true;
    return false;
}

ExtraProperty* SplatCloud::find_extra(const std::string& name) {
    for (auto& extra : extras)
        if (extra.name == name) return &extra;
    return nullptr;
}

const ExtraProperty* SplatCloud::find_extra(const std::string& name) const {
    for (const auto& extra : extras)
        if (extra.name == name) return &extra;
    return nullptr;
}

ExtraProperty& SplatCloud::add_extra(const std::string& name) {
    if (find_extra(name)) engine::fail("splat_lod::SplatCloud::add_extra(): duplicate property \"" + name + "\"");
    extras.push_back({name, std::vector<float>(size(), 0.0f)});
    return extras.back();
}

void SplatCloud::check_consistent() const {
    const std::size_t n = size();
    auto expect = [n](std::size_t actual, std::size_t wanted, const char* what) {
        if (actual != wanted)
            engine::fail(std::string("splat_lod::SplatCloud: ") + what + " has " + std::to_string(actual) +
                         " entries, expected " + std::to_string(wanted) + " for " + std::to_string(n) + " Gaussians");
    };
    if (sh_degree < 0 || sh_degree > kMaxShDegree)
        engine::fail("splat_lod::SplatCloud: sh_degree " + std::to_string(sh_degree) + " is not 0..3");
    expect(rotations.size(), n, "rotations");
    expect(log_scales.size(), n, "log_scales");
    expect(opacity_logits.size(), n, "opacity_logits");
    expect(sh_dc.size(), n, "sh_dc");
    expect(sh_rest.size(), n * sh_rest_stride(), "sh_rest");
    expect(lod_level.size(), n, "lod_level");
    expect(coverage_min.size(), n, "coverage_min");
    expect(coverage_max.size(), n, "coverage_max");
    for (const auto& extra : extras) expect(extra.values.size(), n, extra.name.c_str());
}

void SplatCloud::keep_only(const std::vector<std::uint8_t>& keep) {
    check_consistent();
    if (keep.size() != size()) engine::fail("splat_lod::SplatCloud::keep_only(): mask size differs from size()");
    compact(positions, keep, 1);
    compact(rotations, keep, 1);
    compact(log_scales, keep, 1);
    compact(opacity_logits, keep, 1);
    compact(sh_dc, keep, 1);
    compact(sh_rest, keep, sh_rest_stride());
    compact(lod_level, keep, 1);
    compact(coverage_min, keep, 1);
    compact(coverage_max, keep, 1);
    for (auto& extra : extras) compact(extra.values, keep, 1);
}

namespace {
constexpr std::array<const char*, 3> kLevelHandoverNames{"unknown", "overlapping", "abutting"};  // enum order
}  // namespace

const char* level_handover_name(LevelHandover handover) {
    const auto index = static_cast<std::size_t>(handover);
    return index < kLevelHandoverNames.size() ? kLevelHandoverNames[index] : "unknown";
}

std::optional<LevelHandover> parse_level_handover(const std::string& name) {
    for (std::size_t i = 0; i < kLevelHandoverNames.size(); ++i)
        if (name == kLevelHandoverNames[i]) return static_cast<LevelHandover>(i);
    return std::nullopt;
}

SplatCloud SplatCloud::permuted(const std::vector<std::uint32_t>& order) const {
    check_consistent();
    SplatCloud out;
    out.sh_degree = sh_degree;
    out.level_handover = level_handover;
    for (const auto& extra : extras) out.extras.push_back({extra.name, {}});
    out.resize(order.size());
    const std::size_t stride = sh_rest_stride();
    for (std::size_t j = 0; j < order.size(); ++j) {
        const std::size_t i = order[j];
        if (i >= size())
            engine::fail("splat_lod::SplatCloud::permuted(): index " + std::to_string(i) + " of " +
                         std::to_string(size()));
        out.positions[j] = positions[i];
        out.rotations[j] = rotations[i];
        out.log_scales[j] = log_scales[i];
        out.opacity_logits[j] = opacity_logits[i];
        out.sh_dc[j] = sh_dc[i];
        std::copy_n(sh_rest.begin() + static_cast<std::ptrdiff_t>(i * stride), stride,
                    out.sh_rest.begin() + static_cast<std::ptrdiff_t>(j * stride));
        out.lod_level[j] = lod_level[i];
        out.coverage_min[j] = coverage_min[i];
        out.coverage_max[j] = coverage_max[i];
        for (std::size_t e = 0; e < extras.size(); ++e) out.extras[e].values[j] = extras[e].values[i];
    }
    return out;
}

std::size_t sanitise(SplatCloud& cloud, LoadReport* report) {
    cloud.check_consistent();
    const std::size_t n = cloud.size();
    std::vector<std::uint8_t> keep(n, 1);
    std::size_t non_finite = 0;
    std::size_t zero_rotation = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!finite_gaussian(cloud, i)) {
            keep[i] = 0;
            ++non_finite;
            continue;
        }
        Rotation& r = cloud.rotations[i];
        const double len2 = norm_squared(r);
        if (!(len2 > kMinQuaternionNormSquared)) {
            keep[i] = 0;
            ++zero_rotation;
            continue;
        }
        const double inv = 1.0 / std::sqrt(len2);
        r = {static_cast<float>(r.w * inv), static_cast<float>(r.x * inv), static_cast<float>(r.y * inv),
             static_cast<float>(r.z * inv)};
    }
    if (non_finite + zero_rotation > 0) cloud.keep_only(keep);
    if (report) {
        report->dropped_non_finite += non_finite;
        report->dropped_zero_rotation += zero_rotation;
        report->loaded = cloud.size();
    }
    return non_finite + zero_rotation;
}

namespace {

template <typename T>
void append_values(std::vector<T>& into, std::vector<T>& part) {
    into.insert(into.end(), part.begin(), part.end());
}

// Keeps the extras present in both clouds, in `into`'s order, with the part's values appended.
void append_extras(SplatCloud& into, SplatCloud& part) {
    std::vector<ExtraProperty> kept;
    for (ExtraProperty& extra : into.extras)
        if (ExtraProperty* other = part.find_extra(extra.name)) {
            append_values(extra.values, other->values);
            kept.push_back(std::move(extra));
        }
    into.extras = std::move(kept);
}

}  // namespace

void append_cloud(SplatCloud& into, SplatCloud&& part) {
    part.check_consistent();
    if (into.empty() && into.extras.empty()) {
        into = std::move(part);
        return;
    }
    into.check_consistent();
    const int degree = std::max(into.sh_degree, part.sh_degree);
    into.set_sh_degree(degree);
    part.set_sh_degree(degree);
    append_extras(into, part);
    if (into.level_handover != part.level_handover) into.level_handover = LevelHandover::unknown;
    append_values(into.positions, part.positions);
    append_values(into.rotations, part.rotations);
    append_values(into.log_scales, part.log_scales);
    append_values(into.opacity_logits, part.opacity_logits);
    append_values(into.sh_dc, part.sh_dc);
    append_values(into.sh_rest, part.sh_rest);
    append_values(into.lod_level, part.lod_level);
    append_values(into.coverage_min, part.coverage_min);
    append_values(into.coverage_max, part.coverage_max);
    part = SplatCloud{};
}

}  // namespace splat_lod
