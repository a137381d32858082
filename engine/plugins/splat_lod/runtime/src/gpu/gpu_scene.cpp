#include "gpu/gpu_scene.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <unordered_map>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/gl/compute_step.h"
#include "engine/scene/node.h"
#include "splat_lod/core/compact_gaussians.h"
#include "splat_lod/core/gaussian_extent.h"
#include "splat_lod/gpu_storage.h"
#include "splat_lod/splat_component.h"

namespace splat_lod::gpu {
namespace {

int drawn_degree(const SplatComponent& c) {
    return std::min(c.sh_degree_cap, c.cloud->sh_degree);
}

// World → local directions for SH: the rotation part of the model matrix (columns normalised,
// so uniform and axis-aligned non-uniform scales are removed), transposed.
glm::mat4 inverse_rotation(const glm::mat4& model) {
    glm::mat3 r(model);
    for (int i = 0; i < 3; ++i) {
        const float len = glm::length(r[i]);
        r[i] = len > 0.0f ? r[i] / len : glm::vec3(0.0f);
    }
    return glm::mat4(glm::transpose(r));
}

}  // namespace

namespace {

// The clusters' spheres, a second pass over each cluster's members: the centre of their bounding
// box and the largest distance from it (rounded up so float error never leaves a mean outside).
// Non-finite bounds disable skipping and culling for the cluster.
void fit_spheres(const std::vector<const SplatCloud*>& clouds, std::vector<GpuCluster>& clusters) {
    constexpr std::size_t size = SPLAT_PROJECT_WORKGROUP_SIZE;
    std::size_t global = 0;
    std::vector<glm::vec3> lo(clusters.size(), glm::vec3(std::numeric_limits<float>::max()));
    std::vector<glm::vec3> hi(clusters.size(), glm::vec3(std::numeric_limits<float>::lowest()));
    for (const SplatCloud* cloud : clouds)
        for (std::size_t i = 0; i < cloud->size(); ++i, ++global)
            if (gaussian_is_drawable(*cloud, i)) {
                lo[global / size] = glm::min(lo[global / size], cloud->positions[i]);
                hi[global / size] = glm::max(hi[global / size], cloud->positions[i]);
            }
    global = 0;
    std::vector<double> radius(clusters.size(), 0.0);
    for (std::size_t c = 0; c < clusters.size(); ++c)
        clusters[c].sphere = glm::vec4(lo[c].x <= hi[c].x ? 0.5f * (lo[c] + hi[c]) : glm::vec3(0.0f), 0.0f);
    for (const SplatCloud* cloud : clouds)
        for (std::size_t i = 0; i < cloud->size(); ++i, ++global)
            if (gaussian_is_drawable(*cloud, i)) {
                const std::size_t c = global / size;
                radius[c] =
                    std::max(radius[c], glm::length(glm::dvec3(cloud->positions[i]) - glm::dvec3(clusters[c].sphere)));
            }
    for (std::size_t c = 0; c < clusters.size(); ++c) {
        clusters[c].sphere.w = static_cast<float>(radius[c] * (1.0 + 1e-5) + 1e-7);
        // A non-finite bound (a Gaussian at 1e38, say) disables the cluster rather than culling wrongly.
        const glm::vec4 v = clusters[c].sphere;
        if (!std::isfinite(v.x + v.y + v.z + v.w) || !std::isfinite(clusters[c].bounds.x)) clusters[c].bounds.y = -1.0f;
        if (!std::isfinite(v.x + v.y + v.z + v.w) || !std::isfinite(clusters[c].reach.x)) clusters[c].reach.x = -1.0f;
    }
}

}  // namespace

std::vector<GpuCluster> build_clusters(const std::vector<const SplatCloud*>& clouds) {
    constexpr std::size_t size = SPLAT_PROJECT_WORKGROUP_SIZE;
    std::size_t total = 0;
    for (const SplatCloud* cloud : clouds) total += cloud->size();
    std::vector<GpuCluster> clusters((total + size - 1) / size);
    std::size_t global = 0;
    for (std::uint32_t instance = 0; instance < clouds.size(); ++instance) {
        const SplatCloud& cloud = *clouds[instance];
        for (std::size_t i = 0; i < cloud.size(); ++i, ++global) {
            GpuCluster& c = clusters[global / size];
            const bool first = global % size == 0;
            if (first) {
                c.sphere = glm::vec4(0.0f);
                c.bounds = glm::vec4(0.0f, 0.0f, 0.0f, std::bit_cast<float>(instance));
                c.reach = glm::vec4(0.0f);
            } else if (std::bit_cast<std::uint32_t>(c.bounds.w) != instance) {
                c.bounds.w = -1.0f;  // spans two instances: never skipped
            }
            c.bounds.z = std::max(c.bounds.z, cloud.lod_level.empty() ? 1.0f : static_cast<float>(cloud.lod_level[i]));
            if (!gaussian_is_drawable(cloud, i)) continue;  // never drawn: no bound needed
            // The shorter chord's bound (world/gaussian_extent.h): coverage ≤ 2·e·‖M‖₂·‖J‖₂.
            const double extent = world::gaussian_extent(cloud.log_scales[i], cloud.opacity_logits[i]);
            c.bounds.x = std::max(c.bounds.x, static_cast<float>(extent));
            // The frustum test's reach: the whole α = 1/255 ellipsoid, rounded up.
            const double reach = world::gaussian_reach(cloud.log_scales[i], cloud.opacity_logits[i]);
            c.reach.x = std::max(c.reach.x, static_cast<float>(reach * (1.0 + 1e-5)));
            // The ratio, not the smallest coverage_min: one tiny member would otherwise pin the
            // whole cluster, while e / S_min is about the same for neighbours seen from the same
            // distances.
            const float cmin = cloud.coverage_min.empty() ? -1.0f : cloud.coverage_min[i];
            if (!(cmin > 0.0f) || c.bounds.y < 0.0f)
                c.bounds.y = -1.0f;
            else
                c.bounds.y = std::max(c.bounds.y, static_cast<float>(extent / cmin) * (1.0f + 1e-6f));
        }
    }
    fit_spheres(clouds, clusters);
    return clusters;
}

float spectral_norm(const glm::mat3& m) {
    // Power iteration on MᵀM (symmetric, positive semi-definite); a few steps are exact enough for a
    // bound that is then rounded up.
    const glm::dmat3 a = glm::transpose(glm::dmat3(m)) * glm::dmat3(m);
    glm::dvec3 v(0.577, 0.578, 0.579);
    double lambda = 0.0;
    for (int k = 0; k < 64; ++k) {
        const glm::dvec3 w = a * v;
        const double n = glm::length(w);
        if (!(n > 0.0) || !std::isfinite(n)) break;
        lambda = n;
        v = w / n;
    }
    // Never below the largest column (a lower bound of ‖M‖₂), never above the Frobenius norm.
    const double frobenius = std::sqrt(a[0][0] + a[1][1] + a[2][2]);
    const double column = std::sqrt(std::max({a[0][0], a[1][1], a[2][2]}));
    return static_cast<float>(std::clamp(std::sqrt(lambda) * (1.0 + 1e-4), column, frobenius));
}

namespace {

constexpr std::uint32_t kCluster = SPLAT_PROJECT_WORKGROUP_SIZE;
// What this scene tells budgeters its pages cost (splat_lod/gpu_storage.h) is how it stores them.
static_assert(PageLayout{}.page_gaussians == kCluster);
static_assert(page_layout(GpuStorage::full).page_overhead_bytes == sizeof(GpuCluster));
static_assert(PageLayout{}.page_overhead_bytes == sizeof(GpuCluster) + sizeof(GpuPageCodec));

// A cluster with no members: step 1a drops it in every mode (sphere radius < 0).
GpuCluster empty_cluster() {
    GpuCluster c{};
    c.sphere = glm::vec4(0.0f, 0.0f, 0.0f, -1.0f);
    c.bounds = glm::vec4(0.0f, 0.0f, 0.0f, -1.0f);
    c.reach = glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f);
    return c;
}

}  // namespace

std::uint64_t GpuScene::live_gaussians() const {
    std::uint64_t n = 0;
    for (const Slot& s : slots_)
        if (s.cloud) n += s.cloud->size();
    return n;
}

std::uint32_t GpuScene::pages_in_use() const {
    std::uint32_t n = 0;
    for (const Slot& s : slots_) n += static_cast<std::uint32_t>(s.pages.size());
    return n;
}

std::size_t GpuScene::record_bytes() const {
    return storage_ == GpuStorage::compact ? kCompactWords * sizeof(std::uint32_t) : sizeof(GpuGaussian);
}

std::uint64_t GpuScene::page_bytes() const {
    const std::size_t codec = storage_ == GpuStorage::compact ? sizeof(GpuPageCodec) : 0;
    return std::uint64_t(kCluster) * (record_bytes() + sh_stride_ * sizeof(float)) + sizeof(GpuCluster) + codec;
}

void GpuScene::reserve(std::uint64_t gaussians, int sh_degree, GpuStorage storage) {
    if (sh_degree < 0 || sh_degree > kMaxShDegree)
        engine::fail("splat_lod: SH degree " + std::to_string(sh_degree) + " is not 0..3");
    const std::uint64_t pages = (gaussians + kCluster - 1) / kCluster;
    if (pages * kCluster > std::numeric_limits<std::uint32_t>::max() / 2)
        engine::fail("splat_lod: cannot reserve " + std::to_string(gaussians) + " Gaussians");
    if (sh_degree > sh_degree_ || storage != storage_) reset(std::max(sh_degree, sh_degree_), storage);
    if (pages * kCluster > capacity_) grow(static_cast<std::uint32_t>(pages * kCluster));
}

void GpuScene::reset(int sh_degree, GpuStorage storage) {
    slots_.clear();
    free_.clear();
    capacity_ = 0;
    gaussian_count_ = 0;
    sh_degree_ = sh_degree;
    storage_ = storage;
    sh_stride_ = storage == GpuStorage::compact ? compact_sh_words(sh_degree)
                                                : static_cast<std::uint32_t>(3 * (sh_degree + 1) * (sh_degree + 1));
    gaussians_ = engine::gl::Buffer(engine::gl::NoCreate);
    sh_ = engine::gl::Buffer(engine::gl::NoCreate);
    clusters_ = engine::gl::Buffer(engine::gl::NoCreate);
    codecs_ = engine::gl::Buffer(engine::gl::NoCreate);
}

// Grows the buffers to `capacity` Gaussian slots (whole pages), keeping their contents (a
// GPU-side copy).
void GpuScene::grow(std::uint32_t capacity) {
    auto regrow = [&](engine::gl::Buffer& buffer, std::size_t bytes, const char* label) {
        engine::gl::Buffer bigger(label);
        bigger.storage(bytes);
        if (buffer && buffer.size() > 0) engine::gl::copy_buffer(buffer, bigger, buffer.size());
        buffer = std::move(bigger);
    };
    regrow(gaussians_, std::size_t(capacity) * record_bytes(), "splat gaussians");
    // At least one word: compact storage at degree 0 has no SH bytes, but the binding needs a buffer.
    regrow(sh_, std::max<std::size_t>(std::size_t(capacity) * sh_stride_ * sizeof(float), 4), "splat sh");
    if (storage_ == GpuStorage::compact)
        regrow(codecs_, std::max<std::size_t>(capacity / kCluster, 1) * sizeof(GpuPageCodec), "splat page codecs");
    // New clusters start empty so that pages beyond the end are never drawn.
    const std::size_t old_clusters = capacity_ / kCluster;
    regrow(clusters_, std::max<std::size_t>(capacity / kCluster, 1) * sizeof(GpuCluster), "splat clusters");
    const std::vector<GpuCluster> empty(capacity / kCluster - old_clusters, empty_cluster());
    if (!empty.empty())
        clusters_.upload(old_clusters * sizeof(GpuCluster), empty.size() * sizeof(GpuCluster), empty.data());
    capacity_ = capacity;
}

// Room up to `end` Gaussian slots: the buffers grow to it or by a sixteenth, whichever is more (each growth
// is a copy on the GPU, and what the buffers hold beyond the pages is memory no view can use).
void GpuScene::grow_for(std::uint64_t end) {
    if (end <= capacity_ || end > std::numeric_limits<std::uint32_t>::max() / 2) return;
    const std::uint64_t wanted =
        std::max<std::uint64_t>(end, (std::uint64_t(capacity_) + capacity_ / 16) / kCluster * kCluster);
    grow(static_cast<std::uint32_t>(std::min<std::uint64_t>(wanted, std::numeric_limits<std::uint32_t>::max() / 2)));
}

// The lowest free page, else a new one at the end.
std::uint32_t GpuScene::allocate_page() {
    if (!free_.empty()) {
        const std::uint32_t page = free_.back();
        free_.pop_back();
        return page;
    }
    const std::uint64_t end = std::uint64_t(gaussian_count_) + kCluster;
    if (end > std::numeric_limits<std::uint32_t>::max() / 2)
        engine::fail("splat_lod: " + std::to_string(end) + " Gaussians exceed what one scene can draw");
    grow_for(end);
    gaussian_count_ = static_cast<std::uint32_t>(end);
    return static_cast<std::uint32_t>(end / kCluster - 1);
}

// Frees a slot's pages: their clusters become empty; free pages at the end lower it.
void GpuScene::release(Slot& slot) {
    const GpuCluster empty = empty_cluster();
    for (const std::uint32_t page : slot.pages) {
        clusters_.upload(std::size_t(page) * sizeof(GpuCluster), sizeof(GpuCluster), &empty);
        last_upload_bytes_ += sizeof(GpuCluster);
        free_.push_back(page);
    }
    std::sort(free_.begin(), free_.end(), std::greater<>());
    while (!free_.empty() && std::uint64_t(free_.front() + 1) * kCluster == gaussian_count_) {
        gaussian_count_ -= kCluster;
        free_.erase(free_.begin());
    }
    slot = Slot{};
}

// Uploads a slot's cloud into its pages: Gaussians tagged with the slot's instance index, SH at the
// common stride, one cluster record per page (padding Gaussians have opacity 0). Runs of adjacent
// pages go up in one call.
void GpuScene::place(Slot& slot) {
    const SplatCloud& cloud = *slot.cloud;
    const auto instance = static_cast<std::uint32_t>(&slot - slots_.data());
    const std::size_t pages = std::max<std::size_t>((cloud.size() + kCluster - 1) / kCluster, 1);
    slot.pages.clear();
    // The pages beyond the free ones come at the end: one growth for all of them.
    grow_for(std::uint64_t(gaussian_count_) + (pages - std::min(pages, free_.size())) * kCluster);
    for (std::size_t j = 0; j < pages; ++j) slot.pages.push_back(allocate_page());
    if (storage_ == GpuStorage::compact) {
        std::vector<std::uint32_t> records, sh;
        std::vector<GpuPageCodec> codecs;
        slot.dropped = pack_compact(cloud, slot.sh_degree, instance, records, sh, codecs);
        upload_pages(slot, records.data(), sh.data(), codecs.data());
    } else {
        std::vector<GpuGaussian> gaussians;
        slot.dropped = pack_gaussians(cloud, instance, gaussians);
        GpuGaussian padding{};
        padding.covariance_b.w = std::bit_cast<float>(instance);
        gaussians.resize(pages * kCluster, padding);
        std::vector<float> sh;
        pack_sh(cloud, slot.sh_degree, sh_stride_, sh);
        sh.resize(pages * kCluster * sh_stride_, 0.0f);
        upload_pages(slot, gaussians.data(), sh.data(), nullptr);
    }
    last_upload_bytes_ += pages * page_bytes();
    slot.coarsest = 1;
    for (const std::uint8_t level : cloud.lod_level) slot.coarsest = std::max<std::uint32_t>(slot.coarsest, level);
}

// Runs of adjacent pages go up in one call each; every page gets its cluster record.
void GpuScene::upload_pages(Slot& slot, const void* records, const void* sh, const void* codecs) {
    std::vector<GpuCluster> clusters = build_clusters({slot.cloud.get()});
    const auto instance = static_cast<std::uint32_t>(&slot - slots_.data());
    clusters.resize(slot.pages.size(), empty_cluster());
    for (GpuCluster& c : clusters)
        if (c.bounds.w >= 0.0f) c.bounds.w = std::bit_cast<float>(instance);
    slot.clusters = clusters;
    const std::size_t record_page = kCluster * record_bytes(), sh_page = kCluster * sh_stride_ * sizeof(float);
    const auto* record_bytes_in = static_cast<const std::byte*>(records);
    const auto* sh_bytes_in = static_cast<const std::byte*>(sh);
    for (std::size_t j = 0; j < slot.pages.size();) {
        std::size_t run = 1;
        while (j + run < slot.pages.size() && slot.pages[j + run] == slot.pages[j] + run) ++run;
        const std::size_t page = slot.pages[j];
        gaussians_.upload(page * record_page, run * record_page, record_bytes_in + j * record_page);
        if (sh_page > 0) sh_.upload(page * sh_page, run * sh_page, sh_bytes_in + j * sh_page);
        clusters_.upload(page * sizeof(GpuCluster), run * sizeof(GpuCluster), &clusters[j]);
        if (codecs != nullptr)
            codecs_.upload(page * sizeof(GpuPageCodec), run * sizeof(GpuPageCodec),
                           static_cast<const GpuPageCodec*>(codecs) + j);
        j += run;
    }
}

bool GpuScene::update(const std::vector<const SplatComponent*>& components, GpuStorage storage) {
    last_upload_bytes_ = 0;
    int max_degree = 0;
    for (const auto* c : components) max_degree = std::max(max_degree, drawn_degree(*c));
    // More SH coefficients than the buffers hold, or another storage: start over.
    if (max_degree > sh_degree_ || storage != storage_) reset(std::max(max_degree, sh_degree_), storage);

    std::vector<std::int64_t> slot_of(components.size(), -1);
    std::vector<bool> kept(slots_.size(), false);
    match_resident(components, slot_of, kept);
    bool changed = release_unkept(kept);
    if (place_unmatched(components, slot_of, kept)) changed = true;
    while (!slots_.empty() && !slots_.back().cloud) slots_.pop_back();  // trailing free instances

    tally_slots(changed);
    upload_instances(components, slot_of);
    return changed;
}

// Which resident slot each component keeps (same cloud, same degree); the rest are freed.
// Linear in the number of clouds: a streamed world has thousands of parts every frame.
void GpuScene::match_resident(const std::vector<const SplatComponent*>& components, std::vector<std::int64_t>& slot_of,
                              std::vector<bool>& kept) const {
    std::unordered_multimap<const SplatCloud*, std::size_t> resident;
    for (std::size_t k = 0; k < slots_.size(); ++k)
        if (slots_[k].cloud) resident.emplace(slots_[k].cloud.get(), k);
    for (std::size_t i = 0; i < components.size(); ++i) {
        auto [first, last] = resident.equal_range(components[i]->cloud.get());
        for (auto it = first; it != last; ++it)
            if (slots_[it->second].sh_degree == drawn_degree(*components[i])) {
                kept[it->second] = true;
                slot_of[i] = static_cast<std::int64_t>(it->second);
                resident.erase(it);
                break;
            }
    }
}

// Frees the resident slots no component kept; returns whether there were any.
bool GpuScene::release_unkept(const std::vector<bool>& kept) {
    bool changed = false;
    for (std::size_t k = 0; k < slots_.size(); ++k)
        if (!kept[k] && slots_[k].cloud) {
            release(slots_[k]);
            changed = true;
        }
    return changed;
}

// Places each component that kept no slot in a free instance index, else a new one; returns whether
// there were any.
bool GpuScene::place_unmatched(const std::vector<const SplatComponent*>& components, std::vector<std::int64_t>& slot_of,
                               std::vector<bool>& kept) {
    bool changed = false;
    for (std::size_t i = 0; i < components.size(); ++i) {
        if (slot_of[i] >= 0) continue;
        std::size_t k = 0;  // a free instance index, else a new one
        while (k < slots_.size() && (slots_[k].cloud || kept[k])) ++k;
        if (k == slots_.size()) {
            slots_.emplace_back();
            kept.push_back(false);
        }
        kept[k] = true;
        slots_[k].cloud = components[i]->cloud;
        slots_[k].sh_degree = drawn_degree(*components[i]);
        place(slots_[k]);
        slot_of[i] = static_cast<std::int64_t>(k);
        changed = true;
    }
    return changed;
}

// The scene's totals over the slots; the warning only when the set of clouds changed, not every frame.
void GpuScene::tally_slots(bool changed) {
    dropped_ = 0;
    coarsest_level_ = 1;
    for (const Slot& s : slots_) {
        dropped_ += s.dropped;
        if (s.cloud) coarsest_level_ = std::max(coarsest_level_, s.coarsest);
    }
    if (changed && dropped_ > 0)
        engine::log_warning("splat_lod: " + std::to_string(dropped_) +
                            " Gaussians with NaN/Inf values or a zero rotation are not drawn");
}

// Every instance's transform and record, uploaded every frame (the nodes may have moved).
void GpuScene::upload_instances(const std::vector<const SplatComponent*>& components,
                                const std::vector<std::int64_t>& slot_of) {
    std::vector<GpuInstance> instances(slots_.size());  // free instance indices keep count 0
    instance_components_.assign(slots_.size(), nullptr);
    for (std::size_t i = 0; i < components.size(); ++i) {
        const Slot& slot = slots_[static_cast<std::size_t>(slot_of[i])];
        instance_components_[static_cast<std::size_t>(slot_of[i])] = components[i];
        GpuInstance& inst = instances[static_cast<std::size_t>(slot_of[i])];
        inst.model = components[i]->node()->world_matrix();
        inst.rotation_inverse = inverse_rotation(inst.model);
        // x: the component's opacity factor in [0, 1] (NaN counts as 1), or with `dissolve` the fraction
        // of its Gaussians drawn; at 0 it is drawn as hidden.
        const SplatComponent& component = *components[i];
        const float opacity = std::isnan(component.opacity) ? 1.0f : std::clamp(component.opacity, 0.0f, 1.0f);
        const bool hidden = !component.visible || opacity == 0.0f;
        slots_[static_cast<std::size_t>(slot_of[i])].drawn = !hidden;
        inst.info = glm::uvec4(
            std::bit_cast<std::uint32_t>(opacity), static_cast<std::uint32_t>(slot.cloud->size()),
            static_cast<std::uint32_t>(slot.sh_degree) | (hidden ? std::uint32_t{SPLAT_INSTANCE_HIDDEN} : 0u) |
                (component.dissolve ? std::uint32_t{SPLAT_INSTANCE_DISSOLVE} : 0u) |
                (static_cast<std::uint32_t>(slot.cloud->level_handover) << SPLAT_INSTANCE_HANDOVER_SHIFT),
            std::bit_cast<std::uint32_t>(spectral_norm(glm::mat3(inst.model))));
    }
    const std::size_t bytes = std::max<std::size_t>(instances.size(), 1) * sizeof(GpuInstance);
    instances_.ensure_size(bytes, "splat instances");
    if (!instances.empty()) instances_.upload(0, instances.size() * sizeof(GpuInstance), instances.data());
    for (std::size_t i = 0; i < components.size(); ++i)
        slots_[static_cast<std::size_t>(slot_of[i])].instance = instances[static_cast<std::size_t>(slot_of[i])];
}

}  // namespace splat_lod::gpu
