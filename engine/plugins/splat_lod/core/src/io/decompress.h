#pragma once
// gzip (zlib) and zstd decompression for the SPZ reader. Output grows only as real data is
// produced and never beyond max_output, so a lying header cannot make us allocate more than the
// compressed stream actually expands to.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace splat_lod::io {

// Inflates a gzip stream that starts at the beginning of the file. Stops quietly after max_output
// bytes when stop_early is true (used to peek at a header); otherwise more output than max_output
// is an error. Offsets in messages are compressed-input offsets.
std::vector<std::uint8_t> gunzip(std::span<const std::uint8_t> compressed, std::uint64_t max_output, bool stop_early,
                                 const std::string& name);

// Decompresses one zstd frame that must expand to exactly `expected_size` bytes.
std::vector<std::uint8_t> unzstd(std::span<const std::uint8_t> compressed, std::uint64_t expected_size,
                                 std::uint64_t base_offset, const std::string& name);

}  // namespace splat_lod::io
