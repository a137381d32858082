#pragma once
// Shared by the splat_io_* tests: synthetic clouds, the real files' locations, error capture,
// and test-only SPZ encoders (gzip v2/v3 and zstd v4) so every SPZ decode path can be
// exercised with known values and then corrupted.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "splat_lod/core/splat_cloud.h"

namespace splat_io_test {

// A cloud with varied, finite values: unit quaternions, log-scales in [-6, 1], logits in
// [-5, 5], SH in [-1, 1]; with `lod` also levels 1..4 and coverage ranges; with `extras` two
// extra properties.
splat_lod::SplatCloud make_cloud(std::size_t n, int sh_degree, std::uint32_t seed, bool lod = false,
                                 bool extras = false);

// splats/<relative> in tests/data when it is kept there, else in the shared data folder (data_file).
std::filesystem::path real_splat(const std::string& relative);

// The engine::Error message thrown by `f`, or "" if it returned normally. Any other exception
// type fails the calling test (a reader must only ever throw engine::Error).
std::string error_of(const std::function<void()>& f);

std::vector<std::uint8_t> gzip(std::span<const std::uint8_t> bytes);
std::vector<std::uint8_t> zstd(std::span<const std::uint8_t> bytes);

// SPZ files in the given version (2 or 3: gzip, or the bare payload when !compress; 4: zstd
// streams), quantised the way Niantic's writer does, from a cloud already in SPZ axes.
std::vector<std::uint8_t> encode_spz(const splat_lod::SplatCloud& cloud, int version, bool compress = true);

// A v4 file from raw (uncompressed) streams: each is zstd-compressed and listed in the table of
// contents with `claimed_sizes[k]` as its uncompressed size (the real size when empty).
std::vector<std::uint8_t> spz_v4_file(std::uint32_t num_points, int sh_degree,
                                      const std::vector<std::vector<std::uint8_t>>& streams,
                                      const std::vector<std::uint64_t>& claimed_sizes = {});

// Max |a - b| over all Gaussians of a per-Gaussian scalar accessor.
double max_abs_diff(std::size_t n, const std::function<double(std::size_t)>& difference);

}  // namespace splat_io_test
