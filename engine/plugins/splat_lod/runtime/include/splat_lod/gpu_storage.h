#pragma once
// What the GPU scene's storage costs, stated by the scene's own layout (splat_lod_shared.h) so that
// whoever budgets GPU memory (the chunk streamer, a game sizing its scene) counts bytes the way the
// scene stores them. The GPU scene keeps Gaussians in pages: `page_gaussians` slots, each one
// GpuGaussian plus its SH coefficients, and one GpuCluster record per page.
#include <cstdint>

#include "splat_lod/splat_lod_shared.h"

namespace splat_lod {

// Bytes the GPU scene stores per Gaussian slot: one GpuGaussian (64 bytes) plus its SH coefficients,
// 3·(d + 1)² floats with the DC term included, i.e. 64 + 12·(d + 1)² bytes: 76 at degree 0, 256 at
// degree 3.
constexpr std::uint64_t gpu_bytes_per_gaussian(int sh_degree) {
    const auto coefficients = static_cast<std::uint64_t>((sh_degree + 1) * (sh_degree + 1));
    return sizeof(gpu::GpuGaussian) + 3 * sizeof(float) * coefficients;
}

// How the GPU scene stores one upload: whole pages of `page_gaussians` slots (one project workgroup)
// plus `page_overhead_bytes` per page (its cluster record).
struct PageLayout {
    std::uint32_t page_gaussians = SPLAT_PROJECT_WORKGROUP_SIZE;
    std::uint32_t page_overhead_bytes = sizeof(gpu::GpuCluster);
};

// GPU bytes of one upload of `count` Gaussians stored with SH degree `sh_degree` (0..3): whole
// pages, so ceil(count / page)·(page·per Gaussian + overhead); none for none. The default layout
// {1, 0} counts the slots alone.
constexpr std::uint64_t gpu_bytes(std::uint64_t count, int sh_degree, PageLayout page = {1, 0}) {
    const std::uint64_t pages = (count + page.page_gaussians - 1) / page.page_gaussians;
    return pages * (std::uint64_t(page.page_gaussians) * gpu_bytes_per_gaussian(sh_degree) + page.page_overhead_bytes);
}

// The most Gaussians one upload may hold within `budget` bytes: whole pages (0 when not even one
// page fits).
constexpr std::uint64_t max_gaussians_within(std::uint64_t budget, int sh_degree, PageLayout page) {
    return budget / gpu_bytes(page.page_gaussians, sh_degree, page) * page.page_gaussians;
}

static_assert(gpu_bytes_per_gaussian(0) == 76 && gpu_bytes_per_gaussian(3) == 256);
static_assert(PageLayout{}.page_gaussians == 256 && PageLayout{}.page_overhead_bytes == 48);

}  // namespace splat_lod
