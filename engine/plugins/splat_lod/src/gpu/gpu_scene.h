#pragma once
// The GPU copy of every splat component of a scene: one Gaussian buffer and one SH buffer,
// the clouds concatenated in component order, rebuilt only when the set of clouds (or an SH cap)
// changes; instance transforms are refreshed every frame. Only what the scene needs is resident:
// the SH stride is that of the highest degree actually drawn.
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/gl/objects.h"
#include "gpu/gpu_layout.h"
#include "splat_lod/splat_cloud.h"

namespace splat_lod {

struct SplatComponent;

namespace gpu {

// Converts one cloud's Gaussians (ALGORITHMS §1 activation: exp scales, sigmoid opacity,
// Σ = R S Sᵀ Rᵀ) into GpuGaussian records tagged with `instance`. Gaussians with NaN/Inf values
// or a zero quaternion get opacity 0 (never drawn); returns how many.
std::size_t pack_gaussians(const SplatCloud& cloud, std::uint32_t instance, std::vector<GpuGaussian>& out);
// Appends the SH coefficients up to `degree` (DC first), `stride` floats per Gaussian.
void pack_sh(const SplatCloud& cloud, int degree, std::uint32_t stride, std::vector<float>& out);

// The clusters of the project pass's workgroups over the packed Gaussians of `clouds` (concatenated
// in order, as pack_gaussians packs them): bounding sphere, largest visible extent, smallest
// coverage_min, highest level and instance (GpuCluster in splat_lod_shared.h).
std::vector<GpuCluster> build_clusters(const std::vector<const SplatCloud*>& clouds);

// ‖M‖₂, the largest singular value of a 3×3 matrix (how much the model matrix can stretch a length).
float spectral_norm(const glm::mat3& m);

class GpuScene {
public:
    // Uploads when the components' clouds or SH caps differ from the resident ones; refreshes the
    // instance transforms always. Returns true when the Gaussian buffers were rebuilt.
    bool update(const std::vector<const SplatComponent*>& components);

    std::uint32_t gaussian_count() const { return gaussian_count_; }
    std::uint32_t instance_count() const { return static_cast<std::uint32_t>(resident_.size()); }
    std::uint32_t sh_stride() const { return sh_stride_; }
    std::uint32_t coarsest_level() const { return coarsest_level_; }  // highest LOD level present
    std::size_t dropped() const { return dropped_; }  // not drawable (NaN/Inf, zero rotation)
    std::size_t resident_bytes() const { return gaussians_.size() + sh_.size() + instances_.size() + clusters_.size(); }

    const engine::gl::Buffer& gaussians() const { return gaussians_; }
    const engine::gl::Buffer& sh() const { return sh_; }
    const engine::gl::Buffer& instances() const { return instances_; }
    const engine::gl::Buffer& clusters() const { return clusters_; }

private:
    struct Resident {
        const SplatCloud* cloud;
        int sh_degree;
        bool operator==(const Resident&) const = default;
    };
    void upload(const std::vector<const SplatComponent*>& components, std::vector<Resident> wanted);

    std::vector<Resident> resident_;
    std::vector<std::shared_ptr<const SplatCloud>> keep_alive_;  // the clouds the buffers were made from
    std::uint32_t gaussian_count_ = 0;
    std::size_t dropped_ = 0;
    std::uint32_t sh_stride_ = 3;
    std::uint32_t coarsest_level_ = 1;
    engine::gl::Buffer gaussians_{engine::gl::NoCreate};
    engine::gl::Buffer sh_{engine::gl::NoCreate};
    engine::gl::Buffer instances_{engine::gl::NoCreate};
    engine::gl::Buffer clusters_{engine::gl::NoCreate};
};

}  // namespace gpu
}  // namespace splat_lod
