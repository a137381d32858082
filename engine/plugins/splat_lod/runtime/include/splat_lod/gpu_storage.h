#pragma once
// What the GPU scene's storage costs, stated by the scene's own layout (splat_lod_shared.h and
// splat_lod/core/compact_gaussians.h) so that whoever budgets GPU memory (the chunk streamer, a game
// sizing its scene) counts bytes the way the scene stores them. The GPU scene keeps Gaussians in
// pages: `page_gaussians` slots, each one record plus its SH, and per page one GpuCluster record (and
// with compact storage one GpuPageCodec).
#include <cstdint>

#include "splat_lod/core/compact_gaussians.h"
#include "splat_lod/splat_lod_shared.h"

namespace splat_lod {

// How the GPU scene stores Gaussians (docs/gpu_storage.md). compact: 20 bytes a Gaussian plus 8 or 16
// bytes of higher SH bands, quantised per page, decoded in the project pass; full: float records
// (GpuGaussian, 64 bytes, the covariance precomputed in double) and float SH, for a user who needs
// the trained values to the last bit (comparing against another renderer, say).
enum class GpuStorage : std::uint8_t { compact, full };

// Bytes the GPU scene stores per Gaussian slot. Full: one GpuGaussian (64 bytes) plus 3·(d + 1)²
// floats of SH, i.e. 76 at degree 0 and 256 at degree 3. Compact: the 20-byte record plus the higher
// bands' words, 20, 28, 36 and 36 at degree 0..3.
constexpr std::uint64_t gpu_bytes_per_gaussian(int sh_degree, GpuStorage storage = GpuStorage::compact) {
    if (storage == GpuStorage::compact) return 4 * (kCompactWords + compact_sh_words(sh_degree));
    const auto coefficients = static_cast<std::uint64_t>((sh_degree + 1) * (sh_degree + 1));
    return sizeof(gpu::GpuGaussian) + 3 * sizeof(float) * coefficients;
}

// How the GPU scene stores one upload: whole pages of `page_gaussians` slots (one project workgroup)
// plus `page_overhead_bytes` per page (its cluster record, and its codec when compact).
struct PageLayout {
    std::uint32_t page_gaussians = SPLAT_PROJECT_WORKGROUP_SIZE;
    std::uint32_t page_overhead_bytes = sizeof(gpu::GpuCluster) + sizeof(gpu::GpuPageCodec);
    GpuStorage storage = GpuStorage::compact;
};

// The GPU scene's pages with `storage`.
constexpr PageLayout page_layout(GpuStorage storage) {
    const std::uint32_t codec = storage == GpuStorage::compact ? sizeof(gpu::GpuPageCodec) : 0u;
    return {SPLAT_PROJECT_WORKGROUP_SIZE, static_cast<std::uint32_t>(sizeof(gpu::GpuCluster)) + codec, storage};
}

// GPU bytes of one upload of `count` Gaussians stored with SH degree `sh_degree` (0..3): whole
// pages, so ceil(count / page)·(page·per Gaussian + overhead); none for none. The default layout
// {1, 0} counts the (compact) slots alone.
constexpr std::uint64_t gpu_bytes(std::uint64_t count, int sh_degree, PageLayout page = {1, 0}) {
    const std::uint64_t pages = (count + page.page_gaussians - 1) / page.page_gaussians;
    return pages * (std::uint64_t(page.page_gaussians) * gpu_bytes_per_gaussian(sh_degree, page.storage) +
                    page.page_overhead_bytes);
}

// The most Gaussians one upload may hold within `budget` bytes: whole pages (0 when not even one
// page fits).
constexpr std::uint64_t max_gaussians_within(std::uint64_t budget, int sh_degree, PageLayout page) {
    return budget / gpu_bytes(page.page_gaussians, sh_degree, page) * page.page_gaussians;
}

static_assert(gpu_bytes_per_gaussian(0, GpuStorage::full) == 76 && gpu_bytes_per_gaussian(3, GpuStorage::full) == 256);
static_assert(gpu_bytes_per_gaussian(0) == 20 && gpu_bytes_per_gaussian(1) == 28 && gpu_bytes_per_gaussian(3) == 36);
static_assert(PageLayout{}.page_gaussians == 256 && PageLayout{}.page_overhead_bytes == 128);

}  // namespace splat_lod
