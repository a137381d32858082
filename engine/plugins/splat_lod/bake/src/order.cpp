// The bake's output order (order.h).
#include "order.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/core/error.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/lod_selection.h"
#include "splat_lod/core/parallel_for.h"

namespace splat_lod::bake::detail {

std::vector<std::uint32_t> output_order(const SplatCloud& cloud, const Normaliser& normaliser) {
    std::vector<std::uint64_t> morton(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const glm::dvec3 x = normaliser.apply(glm::dvec3(cloud.positions[i]));
        std::uint64_t code = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const double t = std::clamp((x[axis] + 2.0) / 4.0, 0.0, 1.0) * double((1 << 21) - 1);
            code |= spread_bits(static_cast<std::uint64_t>(t)) << axis;
        }
        morton[i] = code;
    }
    // Size class: log2 of the extent that bounds a Gaussian's coverage (see build_clusters in
    // gpu/gpu_scene.cpp); unseen Gaussians (no range) in a class of their own, last.
    std::vector<int> size_class(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        glm::vec3 s = cloud.log_scales[i];
        std::sort(&s.x, &s.x + 3);
        const double log_extent = std::min(static_cast<double>(s.z), 0.5 * std::log(2.0) + s.y);
        size_class[i] =
            cloud.coverage_min[i] > 0.0f ? static_cast<int>(std::floor(log_extent / std::log(2.0))) : 1 << 20;
    }
    std::vector<std::uint32_t> order(cloud.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        if (cloud.lod_level[a] != cloud.lod_level[b]) return cloud.lod_level[a] > cloud.lod_level[b];
        if (size_class[a] != size_class[b]) return size_class[a] < size_class[b];
        return morton[a] < morton[b];
    });
    return order;
}

}  // namespace splat_lod::bake::detail
