// PlayCanvas SOG: meta.json + lossless WebP textures, one texel per Gaussian in row-major order
// (see sog_meta.h for the two meta layouts). Texel contents:
//   means_l / means_u  RGB = low / high byte of 16-bit x, y, z within the log-space bounds
//   quats              RGB = three smallest components as (q·sqrt(2) + 1)·255/2, A = 252 + index
//                      (in w,x,y,z order) of the largest, rebuilt as sqrt(1 - others²)
//   scales             RGB = log-scale x, y, z (codebook index or range)
//   sh0                RGB = f_dc (codebook index or range), A = opacity (v2) / logit range (v1)
//   shN_labels         RG = 16-bit palette index; shN_centroids: 64 palette entries per row, each
//                      `coefficients` texels wide, texel j's RGB = coefficient j+1 of R, G, B.
// The data come back in the PLY convention, as PlayCanvas's own reader returns them.
#include <algorithm>
#include <cmath>

#include "engine/core/file_io.h"
#include "io_util.h"
#include "readers.h"
#include "splat_lod/core/sog_meta.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/webp_texture.h"

namespace splat_lod {
namespace {

namespace fs = std::filesystem;

constexpr int kPaletteEntriesPerRow = 64;

// Inverse of sign(x)·ln(|x| + 1), the transform SOG applies to positions before quantising.
float inverse_log_transform(float v) {
    return std::copysign(std::expm1(std::fabs(v)), v);
}

fs::path meta_path_of(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_directory(path, ec)) return path;
    if (fs::exists(path / "meta.json", ec)) return path / "meta.json";
    if (fs::exists(path / "lod-meta.json", ec))
        io::fail_file(path.string(),
                      "holds lod-meta.json (a streamed SOG), not meta.json: read it with load_splat_file or "
                      "read_capture");
    io::fail_file(path.string(), "folder has no meta.json");
}

void decode_means(const io::SogMeta& meta, const io::RgbaTexture& lower, const io::RgbaTexture& upper,
                  SplatCloud& cloud) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const std::uint8_t* lo = lower.texel(i);
        const std::uint8_t* hi = upper.texel(i);
        for (int k = 0; k < 3; ++k) {
            const auto axis = static_cast<std::size_t>(k);
            const float t = static_cast<float>(lo[k] | hi[k] << 8) / 65535.0f;
            const float v = meta.means_min[axis] + (meta.means_max[axis] - meta.means_min[axis]) * t;
            cloud.positions[i][k] = inverse_log_transform(v);
        }
    }
}

// Returns the number of texels whose tag byte is not 252..255; those get a zero quaternion, so
// sanitise drops and counts them.
std::size_t decode_quats(const io::RgbaTexture& quats, SplatCloud& cloud) {
    constexpr float kInvSqrt2 = 0.70710678118f;
    std::size_t bad = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const std::uint8_t* t = quats.texel(i);
        if (t[3] < 252) {
            cloud.rotations[i] = {0.0f, 0.0f, 0.0f, 0.0f};
            ++bad;
            continue;
        }
        const int largest = t[3] - 252;
        float q[4];
        float sum = 0.0f;
        for (int k = 0, slot = 0; k < 4; ++k) {
            if (k == largest) continue;
            q[k] = (static_cast<float>(t[slot++]) / 255.0f * 2.0f - 1.0f) * kInvSqrt2;
            sum += q[k] * q[k];
        }
        q[largest] = std::sqrt(std::max(0.0f, 1.0f - sum));
        cloud.rotations[i] = {q[0], q[1], q[2], q[3]};
    }
    return bad;
}

void decode_scales_and_colour(const io::SogMeta& meta, const io::RgbaTexture& scales, const io::RgbaTexture& sh0,
                              SplatCloud& cloud) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const std::uint8_t* s = scales.texel(i);
        const std::uint8_t* c = sh0.texel(i);
        for (std::size_t k = 0; k < 3; ++k) {
            cloud.log_scales[i][static_cast<int>(k)] = meta.scales[k](s[k]);
            cloud.sh_dc[i][static_cast<int>(k)] = meta.colour[k](c[k]);
        }
        cloud.opacity_logits[i] =
            meta.opacity_logit ? (*meta.opacity_logit)(c[3]) : io::unit_to_logit(static_cast<float>(c[3]) / 255.0f);
    }
}

int v1_bands_from_width(int width, const std::string& name) {
    for (int bands = 1; bands <= kMaxShDegree; ++bands)
        if (width == kPaletteEntriesPerRow * sh_rest_coeffs(bands)) return bands;
    io::fail_file(name, "centroid texture width " + std::to_string(width) + " matches no SH band count");
}

// Returns the number of labels outside the palette (their SH stay zero).
std::size_t decode_sh_n(const io::SogShN& sh_n, const io::RgbaTexture& centroids, const io::RgbaTexture& labels,
                        std::uint64_t palette_count, SplatCloud& cloud) {
    const int coeffs = sh_rest_coeffs(cloud.sh_degree);
    std::size_t bad = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const std::uint8_t* l = labels.texel(i);
        const std::uint64_t label = static_cast<std::uint64_t>(l[0] | l[1] << 8);
        if (label >= palette_count) {
            ++bad;
            continue;
        }
        const std::uint64_t row = label / kPaletteEntriesPerRow;
        const std::uint64_t column = (label % kPaletteEntriesPerRow) * static_cast<std::uint64_t>(coeffs);
        for (int k = 0; k < coeffs; ++k) {
            const std::uint8_t* t = centroids.texel(row * static_cast<std::uint64_t>(centroids.width) + column +
                                                    static_cast<std::uint64_t>(k));
            for (int ch = 0; ch < 3; ++ch) cloud.sh_rest_at(i, k + 1, ch) = sh_n.quantiser(t[ch]);
        }
    }
    return bad;
}

void read_sh_n(const io::SogMeta& meta, const fs::path& folder, SplatCloud& cloud, LoadReport& report) {
    const io::SogShN& sh_n = *meta.sh_n;
    io::RgbaTexture centroids = io::load_webp(folder / sh_n.centroids_file, 1);
    const int bands = meta.version == 1 ? v1_bands_from_width(centroids.width, centroids.name) : sh_n.bands;
    const int coeffs = sh_rest_coeffs(bands);
    if (centroids.width != kPaletteEntriesPerRow * coeffs)
        io::fail_file(centroids.name, "width " + std::to_string(centroids.width) + ", expected " +
                                          std::to_string(kPaletteEntriesPerRow * coeffs) + " for " +
                                          std::to_string(bands) + " SH bands");
    const std::uint64_t capacity = static_cast<std::uint64_t>(centroids.height) * kPaletteEntriesPerRow;
    const std::uint64_t palette_count = meta.version == 1 ? capacity : sh_n.palette_count;
    if (palette_count > capacity)
        io::fail_file(centroids.name, "holds " + std::to_string(capacity) + " palette entries, meta.json says " +
                                          std::to_string(palette_count));
    const io::RgbaTexture labels = io::load_webp(folder / sh_n.labels_file, cloud.size());
    cloud.set_sh_degree(bands);
    const std::size_t bad = decode_sh_n(sh_n, centroids, labels, palette_count, cloud);
    if (bad > 0)
        report.warnings.push_back(std::to_string(bad) + " SH palette labels out of range; their SH set to zero");
}

}  // namespace

namespace io {

SplatCloud decode_sog(const std::filesystem::path& path, LoadReport& local) {
    const fs::path meta_file = meta_path_of(path);
    const fs::path folder = meta_file.parent_path();
    const io::SogMeta meta = io::parse_sog_meta(engine::read_text_file(meta_file), meta_file.string());
    local.format = "PlayCanvas SOG v" + std::to_string(meta.version);
    local.gaussians_in_file = static_cast<std::size_t>(meta.count);
    // Every texture must hold `count` texels before the cloud is allocated, so the count in
    // meta.json cannot make us allocate more than the textures really contain.
    const auto lower = io::load_webp(folder / meta.means_lower_file, meta.count);
    const auto upper = io::load_webp(folder / meta.means_upper_file, meta.count);
    const auto quats = io::load_webp(folder / meta.quats_file, meta.count);
    const auto scales = io::load_webp(folder / meta.scales_file, meta.count);
    const auto sh0 = io::load_webp(folder / meta.sh0_file, meta.count);
    SplatCloud cloud;
    cloud.resize(static_cast<std::size_t>(meta.count));
    decode_means(meta, lower, upper, cloud);
    if (const std::size_t bad = decode_quats(quats, cloud); bad > 0)
        local.warnings.push_back(std::to_string(bad) + " quaternion texels have an invalid tag byte");
    decode_scales_and_colour(meta, scales, sh0, cloud);
    if (meta.sh_n) read_sh_n(meta, folder, cloud, local);
    return cloud;
}

}  // namespace io

SplatCloud read_sog(const std::filesystem::path& path, LoadReport* report) {
    LoadReport local;
    SplatCloud cloud = io::decode_sog(path, local);
    io::finish_load(cloud, local, report, meta_path_of(path).string());
    return cloud;
}

}  // namespace splat_lod
