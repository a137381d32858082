#include "splat_io_test_helpers.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>
#include <zlib.h>
#include <zstd.h>

#include "engine/core/error.h"
#include "test_support.h"

namespace splat_io_test {
namespace {

std::uint8_t to_byte(float v) {
    return static_cast<std::uint8_t>(std::clamp(std::round(v), 0.0f, 255.0f));
}

void push_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
}

void push_u64(std::vector<std::uint8_t>& out, std::uint64_t v) {
    for (int k = 0; k < 8; ++k) out.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
}

// (x, y, z, w) -> 2-bit index of the largest, then for the others a sign bit and 9 bits of
// |q|·sqrt(2), the first remaining component ending in the highest bits.
std::uint32_t pack_smallest_three(const splat_lod::Rotation& r) {
    const float q[4] = {r.x, r.y, r.z, r.w};
    unsigned largest = 0;
    for (unsigned i = 1; i < 4; ++i)
        if (std::fabs(q[i]) > std::fabs(q[largest])) largest = i;
    const bool negate = q[largest] < 0.0f;
    std::uint32_t packed = largest;
    for (unsigned i = 0; i < 4; ++i) {
        if (i == largest) continue;
        const std::uint32_t sign = (q[i] < 0.0f) != negate ? 1u : 0u;
        const auto magnitude = static_cast<std::uint32_t>(511.0f * std::fabs(q[i]) * 1.41421356f + 0.5f);
        packed = packed << 10 | sign << 9 | std::min(magnitude, 511u);
    }
    return packed;
}

// The six SPZ arrays of `cloud` in file order.
std::vector<std::vector<std::uint8_t>> spz_arrays(const splat_lod::SplatCloud& cloud, int version) {
    std::vector<std::vector<std::uint8_t>> a(6);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            const auto fixed = static_cast<std::int32_t>(std::lround(cloud.positions[i][k] * 4096.0f));
            for (int b = 0; b < 3; ++b) a[0].push_back(static_cast<std::uint8_t>(fixed >> (8 * b)));
        }
        a[1].push_back(to_byte(255.0f / (1.0f + std::exp(-cloud.opacity_logits[i]))));
        for (int k = 0; k < 3; ++k) a[2].push_back(to_byte(cloud.sh_dc[i][k] * 0.15f * 255.0f + 127.5f));
        for (int k = 0; k < 3; ++k) a[3].push_back(to_byte((cloud.log_scales[i][k] + 10.0f) * 16.0f));
        const splat_lod::Rotation& r = cloud.rotations[i];
        if (version >= 3) {
            push_u32(a[4], pack_smallest_three(r));
        } else {
            const float s = r.w < 0.0f ? -127.5f : 127.5f;  // w >= 0 is implied by the format
            for (float c : {r.x, r.y, r.z}) a[4].push_back(to_byte(c * s + 127.5f));
        }
        for (std::size_t k = 0; k < cloud.sh_rest_stride(); ++k)
            a[5].push_back(to_byte(cloud.sh_rest[i * cloud.sh_rest_stride() + k] * 128.0f + 128.0f));
    }
    return a;
}

}  // namespace

splat_lod::SplatCloud make_cloud(std::size_t n, int sh_degree, std::uint32_t seed, bool lod, bool extras) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    splat_lod::SplatCloud cloud;
    cloud.sh_degree = sh_degree;
    if (extras) {
        cloud.extras.push_back({"filter_3D", {}});
        cloud.extras.push_back({"age", {}});
    }
    cloud.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        cloud.positions[i] = {10.0f * unit(rng), 10.0f * unit(rng), 10.0f * unit(rng)};
        splat_lod::Rotation r{unit(rng), unit(rng), unit(rng), unit(rng)};
        const float len = std::sqrt(r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z);
        cloud.rotations[i] = {r.w / len, r.x / len, r.y / len, r.z / len};
        cloud.log_scales[i] = {-2.5f + 3.5f * unit(rng), -2.5f + 3.5f * unit(rng), -2.5f + 3.5f * unit(rng)};
        cloud.opacity_logits[i] = 5.0f * unit(rng);
        cloud.sh_dc[i] = {unit(rng), unit(rng), unit(rng)};
        for (std::size_t k = 0; k < cloud.sh_rest_stride(); ++k)
            cloud.sh_rest[i * cloud.sh_rest_stride() + k] = unit(rng);
        if (lod) {
            cloud.lod_level[i] = static_cast<std::uint8_t>(1 + i % 4);
            cloud.coverage_min[i] = i % 3 == 0 ? -1.0f : 0.5f * static_cast<float>(i % 7);
            cloud.coverage_max[i] = i % 3 == 0 ? -1.0f : 4.0f + static_cast<float>(i % 5);
        }
        for (auto& extra : cloud.extras) extra.values[i] = 100.0f * unit(rng);
    }
    return cloud;
}

std::filesystem::path real_splat(const std::string& relative) {
    return engine::test::data_file("splats/" + relative);
}

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const engine::Error& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "threw a non-engine exception: " << e.what();
        return e.what();
    }
    return "";
}

std::vector<std::uint8_t> gzip(std::span<const std::uint8_t> bytes) {
    z_stream s{};
    EXPECT_EQ(deflateInit2(&s, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 16 + MAX_WBITS, 9, Z_DEFAULT_STRATEGY), Z_OK);
    std::vector<std::uint8_t> out(deflateBound(&s, static_cast<uLong>(bytes.size())) + 64);
    s.next_in = const_cast<Bytef*>(bytes.data());
    s.avail_in = static_cast<uInt>(bytes.size());
    s.next_out = out.data();
    s.avail_out = static_cast<uInt>(out.size());
    EXPECT_EQ(deflate(&s, Z_FINISH), Z_STREAM_END);
    out.resize(s.total_out);
    deflateEnd(&s);
    return out;
}

std::vector<std::uint8_t> zstd(std::span<const std::uint8_t> bytes) {
    std::vector<std::uint8_t> out(ZSTD_compressBound(bytes.size()));
    const std::size_t size = ZSTD_compress(out.data(), out.size(), bytes.data(), bytes.size(), 3);
    EXPECT_FALSE(ZSTD_isError(size));
    out.resize(size);
    return out;
}

std::vector<std::uint8_t> encode_spz(const splat_lod::SplatCloud& cloud, int version, bool compress) {
    const auto arrays = spz_arrays(cloud, version);
    if (version == 4) {
        const std::size_t streams = cloud.sh_degree > 0 ? 6 : 5;
        return spz_v4_file(static_cast<std::uint32_t>(cloud.size()), cloud.sh_degree,
                           {arrays.begin(), arrays.begin() + static_cast<std::ptrdiff_t>(streams)});
    }
    std::vector<std::uint8_t> out;
    push_u32(out, 0x5053474e);
    push_u32(out, static_cast<std::uint32_t>(version));
    push_u32(out, static_cast<std::uint32_t>(cloud.size()));
    out.push_back(static_cast<std::uint8_t>(cloud.sh_degree));
    out.push_back(12);  // fractional bits
    out.push_back(0);   // flags
    out.push_back(0);
    for (const auto& a : arrays) out.insert(out.end(), a.begin(), a.end());
    return compress ? gzip(out) : out;
}

std::vector<std::uint8_t> spz_v4_file(std::uint32_t num_points, int sh_degree,
                                      const std::vector<std::vector<std::uint8_t>>& streams,
                                      const std::vector<std::uint64_t>& claimed_sizes) {
    std::vector<std::uint8_t> out;
    push_u32(out, 0x5053474e);
    push_u32(out, 4);
    push_u32(out, num_points);
    out.push_back(static_cast<std::uint8_t>(sh_degree));
    out.push_back(12);  // fractional bits
    out.push_back(0);   // flags
    out.push_back(static_cast<std::uint8_t>(streams.size()));
    push_u32(out, 32);  // table of contents right after the header
    out.resize(32, 0);
    std::vector<std::vector<std::uint8_t>> frames;
    for (std::size_t k = 0; k < streams.size(); ++k) {
        frames.push_back(zstd(streams[k]));
        push_u64(out, frames.back().size());
        push_u64(out, k < claimed_sizes.size() ? claimed_sizes[k] : streams[k].size());
    }
    for (const auto& f : frames) out.insert(out.end(), f.begin(), f.end());
    return out;
}

double max_abs_diff(std::size_t n, const std::function<double(std::size_t)>& difference) {
    double worst = 0.0;
    for (std::size_t i = 0; i < n; ++i) worst = std::max(worst, std::fabs(difference(i)));
    return worst;
}

}  // namespace splat_io_test
