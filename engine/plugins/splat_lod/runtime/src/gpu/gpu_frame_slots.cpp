// Which pages of the GPU scene get frame slots (gpu_scene.h, assign_frame_slots).
#include <algorithm>
#include <bit>
#include <cmath>

#include "gpu/gpu_scene.h"

namespace splat_lod::gpu {
namespace {

// The view transform into the camera frame of the project pass (y down the image, z forward).
const glm::dmat3 kViewToCamera(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);

// True only when step 1a's frustum test (cull_cluster in splat_clusters.comp.glsl) surely culls the
// cluster: the same planes in double, with the sphere, the reach and the image's margin all widened far
// beyond the float rounding of the GPU's test, so that every cluster the GPU keeps has slots.
bool surely_outside(const GpuCluster& c, const GpuInstance& instance, const FrameUniforms& u) {
    if (u.frustum_culling == 0 || !(c.reach.x >= 0.0f) || c.bounds.w < 0.0f) return false;
    const double stretch = std::bit_cast<float>(instance.info.w);
    const glm::dvec4 world = glm::dmat4(instance.model) * glm::dvec4(glm::dvec3(c.sphere), 1.0);
    const glm::dvec3 p = kViewToCamera * glm::dvec3(glm::dmat4(u.view) * world);
    const double radius = c.sphere.w * stretch * 1.01;
    const double slack = 1e-3 * (glm::length(p) + radius) + 1e-6;
    if (!std::isfinite(glm::length(p) + radius)) return false;
    if (p.z + radius + slack < u.znear) return true;
    const double fx = u.focal.x, fy = u.focal.y, lx = u.jacobian_clamp.x, ly = u.jacobian_clamp.y;
    const double j = std::sqrt(fx * fx * (1.0 + lx * lx) + fy * fy * (1.0 + ly * ly));
    const double reach = c.reach.x * stretch * j * 1.01 + 1.0;
    const double margin = 2.0 + std::sqrt(2.0 * std::log(255.0) * std::max(double(u.dilation), 0.0)) * 1.01;
    const glm::dvec3 sides[4] = {{fx, 0.0, -(u.raster_size.x + margin - u.principal.x)},
                                 {-fx, 0.0, -(u.principal.x + margin)},
                                 {0.0, fy, -(u.raster_size.y + margin - u.principal.y)},
                                 {0.0, -fy, -(u.principal.y + margin)}};
    for (const glm::dvec3& n : sides) {
        const double length = glm::length(n);
        if (glm::dot(n, p) - radius * length > reach + slack * length) return true;
    }
    return false;
}

}  // namespace

void GpuScene::assign_frame_slots(const FrameUniforms& view) {
    std::vector<std::uint32_t> table(gaussian_count_ / SPLAT_PROJECT_WORKGROUP_SIZE, SPLAT_NO_SLOT);
    for (const Slot& slot : slots_) {
        if (!slot.cloud || !slot.drawn) continue;
        for (std::size_t j = 0; j < slot.pages.size(); ++j)
            if (!surely_outside(slot.clusters[j], slot.instance, view)) table[slot.pages[j]] = 0;
    }
    std::uint32_t next = 0;
    for (std::uint32_t& first : table)
        if (first == 0) first = next++;
    slot_count_ = std::max<std::uint32_t>(next, 1) * SPLAT_PROJECT_WORKGROUP_SIZE;  // no pass has zero length
    if (table == frame_slots_ && cluster_slots_) return;
    cluster_slots_.ensure_size(std::max<std::size_t>(table.size(), 1) * sizeof(std::uint32_t), "splat cluster slots");
    if (!table.empty()) cluster_slots_.upload(0, table.size() * sizeof(std::uint32_t), table.data());
    frame_slots_ = std::move(table);
}

}  // namespace splat_lod::gpu
