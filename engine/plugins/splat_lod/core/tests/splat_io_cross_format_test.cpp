// biker.compressed.ply and biker.spz hold the same capture. After converting the SPZ's RUB axes to
// the PLY convention they must agree Gaussian by Gaussian (both files keep the same order) within
// the sum of the two formats' quantisation errors:
//   position  compressed PLY: half a step of 11/10/11 bits across the chunk's bounds;
//             SPZ: half a step of 2^-12 (12 fractional bits)
//   log-scale compressed PLY: half a step of 11/10/11 bits across the chunk's scale bounds;
//             SPZ: half a step of 1/16, and clamped to [-10, 5.9375]
//   colour    (0.5 + C0·dc) compressed PLY: half a step of 8 bits across the chunk's colour
//             bounds; SPZ: dc·0.15 in 8 bits, i.e. 0.5/255·C0/0.15 in colour
//   opacity   both 8 bits of sigmoid(logit): 0.5/255 each
//   rotation  compressed PLY: 10 bits for components in ±1/sqrt(2); SPZ: sign + 9 bits of the
//             magnitude; per format the three stored components err by ≤ δ ≈ 6.9e-4 and the
//             rebuilt largest one (≥ 1/2) by ≤ 3·(1/sqrt(2))·δ/(1/2) ≈ 4.2δ, so |Δq| ≤ 4.6δ;
//             compared up to sign (q and -q are the same rotation).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>

#include <gtest/gtest.h>

#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"
#include "test_support.h"

using splat_io_test::real_splat;
using splat_lod::SplatCloud;

namespace {

// The 18 floats per chunk of a compressed PLY (min xyz, max xyz, min scale xyz, max scale xyz,
// min rgb, max rgb), read straight from the file so the test does not trust the reader.
std::vector<std::array<float, 18>> chunk_bounds(const std::filesystem::path& path, std::size_t chunks) {
    const auto bytes = engine::read_binary_file(path);
    const std::string text(bytes.begin(), bytes.begin() + 4096);
    const std::size_t data = text.find("end_header\n") + 11;
    std::vector<std::array<float, 18>> out(chunks);
    for (std::size_t c = 0; c < chunks; ++c) std::memcpy(out[c].data(), bytes.data() + data + c * 72, 72);
    return out;
}

struct Stats {
    const char* name;
    double max = 0.0;
    double sum = 0.0;
    double worst_margin = -1e30;  // max of (difference - tolerance); must stay <= 0
    std::size_t count = 0;

    void add(double difference, double tolerance) {
        max = std::max(max, difference);
        sum += difference;
        worst_margin = std::max(worst_margin, difference - tolerance);
        ++count;
    }
    void print() const {
        std::cout << "[ biker    ] " << name << ": max " << max << ", mean " << sum / static_cast<double>(count)
                  << ", worst (difference - tolerance) " << worst_margin << "\n";
    }
};

double half_step(float lo, float hi, int bits) {
    return (static_cast<double>(hi) - lo) / (2.0 * ((1 << bits) - 1));
}

double sigmoid(double x) {
    return 1.0 / (1.0 + std::exp(-x));
}

}  // namespace

TEST(SplatIoCrossFormat, BikerCompressedPlyMatchesBikerSpzWithinQuantisation) {
    ENGINE_REQUIRE_SHARED_DATA();
    const SplatCloud ply = splat_lod::read_ply(real_splat("playcanvas-engine/biker.compressed.ply"));
    SplatCloud spz = splat_lod::read_spz(real_splat("playcanvas-engine/biker.spz"));
    ASSERT_EQ(ply.size(), 152746u);
    ASSERT_EQ(spz.size(), ply.size());
    // As stored, the SPZ has y and z negated (RUB axes).
    EXPECT_NEAR(spz.positions[0].y, -ply.positions[0].y, 1e-3f);
    EXPECT_NEAR(spz.positions[0].z, -ply.positions[0].z, 1e-3f);
    splat_lod::convert_spz_axes_to_ply(spz);
    ASSERT_EQ(spz.size(), ply.size()) << "same Gaussians, matched by index";
    const auto bounds = chunk_bounds(real_splat("playcanvas-engine/biker.compressed.ply"), (ply.size() + 255) / 256);

    constexpr double kFloat = 1e-5;  // float32 rounding in both decoders
    const double spz_position = 0.5 / 4096.0;
    const double spz_scale = 0.5 / 16.0;
    const double spz_colour = 0.5 / 255.0 * splat_lod::kShC0 / 0.15;
    const double opacity_tol = 2 * 0.5 / 255.0;
    const double rotation_tol = 2 * 4.6 * 0.5 * std::sqrt(2.0) / 1023.0;
    Stats position{"position"}, scale{"log-scale"}, colour{"colour"}, opacity{"opacity"}, rotation{"rotation"};
    const int bits[3] = {11, 10, 11};
    for (std::size_t i = 0; i < ply.size(); ++i) {
        const auto& b = bounds[i / 256];
        for (int k = 0; k < 3; ++k) {
            const auto a = static_cast<std::size_t>(k);
            position.add(std::fabs(ply.positions[i][k] - spz.positions[i][k]),
                         half_step(b[a], b[3 + a], bits[k]) + spz_position + kFloat);
            // SPZ cannot store log-scales outside [-10, 5.9375]: compare with the clamped value.
            const float clamped = std::clamp(ply.log_scales[i][k], -10.0f, 5.9375f);
            scale.add(std::fabs(clamped - spz.log_scales[i][k]),
                      half_step(b[6 + a], b[9 + a], bits[k]) + spz_scale + kFloat);
            const double c_ply = 0.5 + splat_lod::kShC0 * ply.sh_dc[i][k];
            const double c_spz = 0.5 + splat_lod::kShC0 * spz.sh_dc[i][k];
            const double c_limit = splat_lod::kShC0 * 0.5 / 0.15;  // SPZ's byte range in colour
            colour.add(std::fabs(std::clamp(c_ply, 0.5 - c_limit, 0.5 + c_limit) - c_spz),
                       half_step(b[12 + a], b[15 + a], 8) + spz_colour + kFloat);
        }
        opacity.add(std::fabs(sigmoid(ply.opacity_logits[i]) - sigmoid(spz.opacity_logits[i])), opacity_tol + kFloat);
        const auto& p = ply.rotations[i];
        const auto& s = spz.rotations[i];
        auto distance = [&](double sign) {
            const double dw = p.w - sign * s.w, dx = p.x - sign * s.x, dy = p.y - sign * s.y, dz = p.z - sign * s.z;
            return std::sqrt(dw * dw + dx * dx + dy * dy + dz * dz);
        };
        rotation.add(std::min(distance(1.0), distance(-1.0)), rotation_tol + kFloat);
    }
    for (const Stats* s : {&position, &scale, &colour, &opacity, &rotation}) {
        s->print();
        EXPECT_LE(s->worst_margin, 0.0) << s->name << " differs by more than the formats' quantisation";
    }
}
