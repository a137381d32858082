#pragma once
// The GPU copy of every splat component of a scene: one Gaussian buffer and one SH buffer made of
// pages (GpuScene below), a cloud uploaded when its component arrives and its pages freed when it
// leaves; instance transforms and visibility are refreshed every frame. Only what the scene needs is
// resident: the SH stride is that of the highest degree actually drawn.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/gl/objects.h"
#include "gpu/gpu_layout.h"
#include "splat_lod/core/splat_cloud.h"
#include "splat_lod/gpu_storage.h"

namespace splat_lod {

struct SplatComponent;

namespace gpu {

// Converts one cloud's Gaussians (docs/algorithms.md §1 activation: exp scales, sigmoid opacity,
// Σ = R S Sᵀ Rᵀ) into GpuGaussian records tagged with `instance`. Gaussians with NaN/Inf values
// or a zero quaternion get opacity 0 (never drawn); returns how many.
std::size_t pack_gaussians(const SplatCloud& cloud, std::uint32_t instance, std::vector<GpuGaussian>& out);
// Appends the SH coefficients up to `degree` (DC first), `stride` floats per Gaussian.
void pack_sh(const SplatCloud& cloud, int degree, std::uint32_t stride, std::vector<float>& out);
// The compact storage of one cloud (splat_lod/core/compact_gaussians.h) in pages of
// SPLAT_PROJECT_WORKGROUP_SIZE, the last padded with never-drawn records: kCompactWords words per
// Gaussian, `sh_words` per Gaussian of SH bands 1..degree, and one codec per page tagged with `instance`.
// Returns how many Gaussians are not drawable (stored as zeros, never drawn), as pack_gaussians does.
std::size_t pack_compact(const SplatCloud& cloud, int degree, std::uint32_t instance,
                         std::vector<std::uint32_t>& records, std::vector<std::uint32_t>& sh,
                         std::vector<GpuPageCodec>& codecs);

// The clusters of the project pass's workgroups over the packed Gaussians of `clouds` (concatenated
// in order, as pack_gaussians packs them): bounding sphere, largest visible extent, smallest
// coverage_min, highest level and instance (GpuCluster in splat_lod_shared.h).
std::vector<GpuCluster> build_clusters(const std::vector<const SplatCloud*>& clouds);

// ‖M‖₂, the largest singular value of a 3×3 matrix (how much the model matrix can stretch a length).
float spectral_norm(const glm::mat3& m);

// Gaussians of every component live in one buffer made of pages of SPLAT_PROJECT_WORKGROUP_SIZE
// slots, one cluster each; a cloud takes whole pages (not necessarily adjacent), so clusters never
// mix clouds and freed pages fit any later cloud (no fragmentation). Adding a cloud uploads only
// its pages (freed pages first, lowest first, else new ones at the end, growing the buffers by a
// GPU-side copy when full); removing one marks its clusters empty, which step 1a drops in every
// mode. This is what makes streaming affordable: a chunk level that arrives costs its own bytes,
// not a re-upload of the scene. Only a cloud needing more SH coefficients than the buffers hold
// rebuilds everything, as does a change of storage.
class GpuScene {
public:
    // Uploads the clouds that are new since the last call, frees those that are gone, and
    // refreshes the instance transforms, storing Gaussians as `storage` says. Returns true when
    // anything was uploaded or freed.
    bool update(const std::vector<const SplatComponent*>& components, GpuStorage storage = GpuStorage::compact);
    GpuStorage storage() const { return storage_; }

    // Gaussian slots up to the end of the last page in use (what step 1a walks).
    std::uint32_t gaussian_count() const { return gaussian_count_; }
    std::uint32_t instance_count() const { return static_cast<std::uint32_t>(slots_.size()); }
    int sh_degree() const { return std::max(sh_degree_, 0); }         // the SH degree the buffers store
    std::uint32_t sh_stride() const { return sh_stride_; }            // floats (full) or words (compact) per Gaussian
    std::uint32_t coarsest_level() const { return coarsest_level_; }  // highest LOD level present
    std::size_t dropped() const { return dropped_; }                  // not drawable (NaN/Inf, zero rotation)
    std::size_t resident_bytes() const {
        return gaussians_.size() + sh_.size() + instances_.size() + clusters_.size() + codecs_.size();
    }
    // Bytes sent to the GPU by the last update() for Gaussians, SH and clusters (GPU-side copies
    // when the buffers grow are not uploads and are not counted).
    std::uint64_t last_upload_bytes() const { return last_upload_bytes_; }
    // Gaussians of the resident clouds (without the padding of their last pages).
    std::uint64_t live_gaussians() const;
    // Pages in use and free below the end; bytes one page costs (Gaussians, SH, cluster record, codec).
    std::uint32_t pages_in_use() const;
    std::uint32_t free_pages() const { return static_cast<std::uint32_t>(free_.size()); }
    std::uint64_t page_bytes() const;
    // Makes room for `gaussians` slots (rounded up to pages) with SH up to `sh_degree` now, so that
    // a streamed world of a known budget never grows or rebuilds the buffers while running. A
    // higher degree than the resident one starts the scene over (what update() would do).
    void reserve(std::uint64_t gaussians, int sh_degree, GpuStorage storage = GpuStorage::compact);

    const engine::gl::Buffer& gaussians() const { return gaussians_; }
    const engine::gl::Buffer& sh() const { return sh_; }
    const engine::gl::Buffer& instances() const { return instances_; }
    // This frame's component of each instance index (null for a free index), as update() placed them.
    const std::vector<const SplatComponent*>& instance_components() const { return instance_components_; }
    const engine::gl::Buffer& clusters() const { return clusters_; }
    const engine::gl::Buffer& page_codecs() const { return codecs_; }  // compact storage only

private:
    struct Slot {  // one instance index; `cloud` null when free
        std::shared_ptr<const SplatCloud> cloud;
        int sh_degree = 0;
        std::vector<std::uint32_t> pages;  // page j holds the cloud's Gaussians [256·j, 256·(j + 1))
        std::uint32_t coarsest = 1;
        std::size_t dropped = 0;
        std::vector<GpuCluster> clusters;  // the cluster record of each page, as uploaded
        GpuInstance instance{};            // this frame's record
        bool drawn = false;                // resident and not hidden this frame
    };
    void reset(int sh_degree, GpuStorage storage);
    std::size_t record_bytes() const;  // bytes of one Gaussian's record
    // Uploads page-sized runs of the slot's `records`, `sh` and `codecs` (per page) into its pages, and
    // keeps its cluster records.
    void upload_pages(Slot& slot, const void* records, const void* sh, const void* codecs);
    std::uint32_t allocate_page();
    void grow_for(std::uint64_t end);
    void release(Slot& slot);
    void place(Slot& slot);
    void grow(std::uint32_t capacity);
    // The steps of update(): `slot_of` is each component's slot (−1 until it has one), `kept` whether
    // a slot is taken this update.
    void match_resident(const std::vector<const SplatComponent*>& components, std::vector<std::int64_t>& slot_of,
                        std::vector<bool>& kept) const;
    bool release_unkept(const std::vector<bool>& kept);
    bool place_unmatched(const std::vector<const SplatComponent*>& components, std::vector<std::int64_t>& slot_of,
                         std::vector<bool>& kept);
    void tally_slots(bool changed);
    void upload_instances(const std::vector<const SplatComponent*>& components,
                          const std::vector<std::int64_t>& slot_of);

    std::vector<Slot> slots_;
    std::vector<const SplatComponent*> instance_components_;
    std::vector<std::uint32_t> free_;  // free pages below the end, sorted descending (lowest at the back)
    std::uint32_t capacity_ = 0;       // Gaussian slots the buffers hold (whole pages)
    std::uint32_t gaussian_count_ = 0;
    std::uint64_t last_upload_bytes_ = 0;
    std::size_t dropped_ = 0;
    int sh_degree_ = -1;  // the degree the SH stride holds; −1 before the first upload
    GpuStorage storage_ = GpuStorage::compact;
    std::uint32_t sh_stride_ = 3;
    std::uint32_t coarsest_level_ = 1;
    engine::gl::Buffer gaussians_{engine::gl::NoCreate};
    engine::gl::Buffer sh_{engine::gl::NoCreate};
    engine::gl::Buffer instances_{engine::gl::NoCreate};
    engine::gl::Buffer clusters_{engine::gl::NoCreate};
    engine::gl::Buffer codecs_{engine::gl::NoCreate};
};

}  // namespace gpu
}  // namespace splat_lod
