// What the GPU scene stores per Gaussian (gpu_scene.h): full GpuGaussian records with float SH, or the
// compact records with SH words and one codec per page (splat_lod/core/compact_gaussians.h).
#include <algorithm>
#include <bit>
#include <numeric>
#include <span>

#include <glm/gtc/quaternion.hpp>

#include "gpu/gpu_scene.h"
#include "splat_lod/core/compact_gaussians.h"
#include "splat_lod/core/gaussian_extent.h"
#include "splat_lod/core/parallel_for.h"

namespace splat_lod::gpu {
namespace {

constexpr std::size_t kPagesPerThread = 64;  // below this an upload is encoded on the calling thread

}  // namespace

std::size_t pack_gaussians(const SplatCloud& cloud, std::uint32_t instance, std::vector<GpuGaussian>& out) {
    out.reserve(out.size() + cloud.size());
    const float instance_bits = std::bit_cast<float>(instance);
    std::size_t dropped = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!gaussian_is_drawable(cloud, i)) {
            // Kept in place (indices stay aligned with the SH buffer) but never drawn: opacity 0.
            GpuGaussian g{};
            g.covariance_b.w = instance_bits;
            out.push_back(g);
            ++dropped;
            continue;
        }
        const Rotation& q = cloud.rotations[i];
        const glm::dmat3 r = glm::mat3_cast(glm::normalize(glm::dquat(q.w, q.x, q.y, q.z)));
        const glm::dvec3 s = glm::exp(glm::dvec3(cloud.log_scales[i]));
        glm::dmat3 m = r;
        for (int c = 0; c < 3; ++c) m[c] *= s[c];
        const glm::dmat3 sigma = m * glm::transpose(m);
        GpuGaussian g;
        g.position_opacity =
            glm::vec4(cloud.positions[i], static_cast<float>(world::opacity_from_logit(cloud.opacity_logits[i])));
        g.covariance_a = glm::vec4(sigma[0][0], sigma[0][1], sigma[0][2], sigma[1][1]);
        g.covariance_b =
            glm::vec4(static_cast<float>(sigma[1][2]), static_cast<float>(sigma[2][2]), 0.0f, instance_bits);
        const float level = cloud.lod_level.empty() ? 1.0f : static_cast<float>(cloud.lod_level[i]);
        const float cmin = cloud.coverage_min.empty() ? -1.0f : cloud.coverage_min[i];
        const float cmax = cloud.coverage_max.empty() ? -1.0f : cloud.coverage_max[i];
        g.lod = glm::vec4(cmin, cmax, level, 0.0f);
        out.push_back(g);
    }
    return dropped;
}

void pack_sh(const SplatCloud& cloud, int degree, std::uint32_t stride, std::vector<float>& out) {
    const std::size_t base = out.size();
    out.resize(base + cloud.size() * stride, 0.0f);
    const int rest = sh_rest_coeffs(degree);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        float* dst = &out[base + i * stride];
        dst[0] = cloud.sh_dc[i].x;
        dst[1] = cloud.sh_dc[i].y;
        dst[2] = cloud.sh_dc[i].z;
        for (int k = 1; k <= rest; ++k)
            for (int c = 0; c < 3; ++c) dst[k * 3 + c] = cloud.sh_rest_at(i, k, c);
    }
}

std::size_t pack_compact(const SplatCloud& cloud, int degree, std::uint32_t instance,
                         std::vector<std::uint32_t>& records, std::vector<std::uint32_t>& sh,
                         std::vector<GpuPageCodec>& codecs) {
    constexpr std::size_t size = SPLAT_PROJECT_WORKGROUP_SIZE;
    const std::size_t pages = std::max<std::size_t>((cloud.size() + size - 1) / size, 1);
    const std::uint32_t sh_words = compact_sh_words(degree);
    records.assign(pages * size * kCompactWords, 0u);  // padding: opacity 0, never drawn
    sh.assign(pages * size * sh_words, 0u);
    codecs.assign(pages, GpuPageCodec{});
    // Pages are encoded on their own, so a large upload spreads them over the cores (a page's SH search
    // costs a few microseconds a Gaussian at degree 3).
    std::vector<std::size_t> dropped(pages, 0);
    const int threads = pages >= kPagesPerThread ? 0 : 1;
    reference::detail::parallel_for(pages, threads, [&](std::size_t page) {
        const CompactPage p = fit_compact_page(cloud, page * size, size, degree);
        codecs[page] =
            GpuPageCodec{glm::vec4(p.position_lo, p.log_scale_lo), glm::vec4(p.position_step, p.log_scale_step),
                         glm::vec4(p.colour_lo, p.coverage_lo), glm::vec4(p.colour_step, p.coverage_step),
                         glm::vec4(p.sh_max, std::bit_cast<float>(instance))};
        for (std::size_t i = page * size; i < std::min((page + 1) * size, cloud.size()); ++i) {
            if (!gaussian_is_drawable(cloud, i)) {  // its record and SH stay zero: opacity 0
                ++dropped[page];
                continue;
            }
            const CompactRecord r = encode_compact(cloud, i, p);
            std::copy(r.begin(), r.end(), records.begin() + static_cast<std::ptrdiff_t>(i * kCompactWords));
            encode_compact_sh(cloud, i, p, degree, std::span(sh).subspan(i * sh_words, sh_words));
        }
    });
    return std::accumulate(dropped.begin(), dropped.end(), std::size_t{0});
}

}  // namespace splat_lod::gpu
