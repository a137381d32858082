#pragma once
// PlayCanvas SOG meta.json, validated into a version-independent description.
//   v1 (no "version"): count = means.shape[0]; scales and sh0 are per-channel linear ranges
//       (mins/maxs, sh0's 4th channel a range of opacity logits); shN a scalar range, its band
//       count implied by the centroid texture width (64 entries per row × coefficients).
//   v2 ("version": 2): count; scales, sh0 and shN use 256-entry codebooks; sh0's alpha is the
//       activated opacity; shN gives its palette size ("count") and "bands".
// Both: means mins/maxs bound sign(x)·ln(|x| + 1) of the positions, stored as 16 bits split
// over means_l (low byte) and means_u (high byte).
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace splat_lod::io {

// 256 decoded values (v2) or a linear range lo + (hi - lo)·byte/255 (v1).
struct SogQuantiser {
    std::vector<float> codebook;
    float lo = 0.0f;
    float hi = 1.0f;

    float operator()(std::uint8_t byte) const {
        return codebook.empty() ? lo + (hi - lo) * static_cast<float>(byte) / 255.0f : codebook[byte];
    }
};

struct SogShN {
    int bands = 0;                    // v2 only; v1 infers it from the centroid texture
    std::uint64_t palette_count = 0;  // v2 only
    SogQuantiser quantiser;
    std::string centroids_file;
    std::string labels_file;
};

struct SogMeta {
    int version = 1;
    std::uint64_t count = 0;
    std::array<float, 3> means_min{};
    std::array<float, 3> means_max{};
    std::string means_lower_file;
    std::string means_upper_file;
    std::array<SogQuantiser, 3> scales;  // per axis (v2: the same codebook thrice)
    std::string scales_file;
    std::string quats_file;
    std::array<SogQuantiser, 3> colour;         // per channel
    std::optional<SogQuantiser> opacity_logit;  // v1: a range of logits; v2: none (alpha = opacity)
    std::string sh0_file;
    std::optional<SogShN> sh_n;
};

// Parses meta.json; every problem is an engine::Error naming the file and the JSON key.
SogMeta parse_sog_meta(const std::string& text, const std::string& name);

}  // namespace splat_lod::io
