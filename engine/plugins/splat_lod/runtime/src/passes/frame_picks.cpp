// Picking in the splat frame (frame_picks.h).
#include "passes/frame_picks.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "engine/gl/compute_step.h"
#include "gpu/gpu_layout.h"
#include "splat_lod/splat_component.h"

namespace splat_lod {

static_assert(SPLAT_MAX_PICKS == engine::kMaxPicksPerFrame, "a frame's picks fit the GPU's list");
static_assert(sizeof(gpu::SplatPicks) == 16 + 2 * 16 * SPLAT_MAX_PICKS, "std430 layout of SplatPicks");

bool FramePicks::upload(std::span<const engine::PickRequest> requests, float scale, glm::ivec2 raster_size,
                        engine::gl::Buffer& picks) {
    requests_.assign(requests.begin(), requests.begin() + std::min<std::size_t>(requests.size(), SPLAT_MAX_PICKS));
    if (requests_.empty()) return false;
    gpu::SplatPicks data{};
    data.count = glm::uvec4(static_cast<std::uint32_t>(requests_.size()), 0u, 0u, 0u);
    for (std::size_t k = 0; k < requests_.size(); ++k) {
        // Below render scale 1 the raster's texel whose footprint holds the pixel's centre.
        const glm::ivec2 pixel = requests_[k].pixel;
        const glm::ivec2 texel =
            glm::clamp(glm::ivec2(glm::floor((glm::vec2(pixel) + 0.5f) * scale)), glm::ivec2(0), raster_size - 1);
        data.pixels[k] = glm::uvec4(glm::uvec2(texel), glm::uvec2(pixel));
    }
    picks.ensure_size(sizeof(gpu::SplatPicks), "splat picks");
    picks.upload(0, sizeof(data), &data);
    return true;
}

void FramePicks::record(const engine::gl::Buffer& picks, const engine::CameraView& camera,
                        std::vector<const SplatComponent*> components) {
    Readback& r = readbacks_[frames_ % readbacks_.size()];
    if (r.fence.pending()) collect(r);  // all four in flight: rare, bounded
    if (!r.buffer) {
        r.buffer = engine::gl::Buffer("splat picks readback");
        r.buffer.storage(sizeof(gpu::SplatPicks), nullptr, GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
    }
    engine::gl::memory_barrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    engine::gl::copy_buffer(picks, r.buffer, sizeof(gpu::SplatPicks));
    r.fence.insert();
    r.requests = std::move(requests_);
    requests_.clear();
    r.camera = camera;
    r.components = std::move(components);
    ++frames_;
}

void FramePicks::collect(Readback& r) {
    gpu::SplatPicks data;
    engine::gl::read_buffer(r.buffer, 0, sizeof(data), &data);  // waits for the copy when it is not done
    r.fence.reset();
    for (std::size_t k = 0; k < r.requests.size(); ++k) {
        const float depth = std::bit_cast<float>(data.answers[k].x);
        const std::uint32_t instance = data.answers[k].y;
        std::optional<engine::PickHit> hit;
        if (std::isfinite(depth) && instance < r.components.size() && r.components[instance] != nullptr) {
            const SplatComponent* component = r.components[instance];
            hit = engine::PickHit{engine::pixel_ray_point(r.camera, r.requests[k].pixel, depth), depth,
                                  component->node(), component};
        }
        answers_.add(r.requests[k].ticket, hit);
    }
    r.requests.clear();
    r.components.clear();
}

engine::PickResult FramePicks::answer(std::uint64_t ticket, bool wait) {
    for (Readback& r : readbacks_) {
        if (!r.fence.pending()) continue;
        const bool asked = std::any_of(r.requests.begin(), r.requests.end(),
                                       [&](const engine::PickRequest& q) { return q.ticket == ticket; });
        if (!asked) continue;
        if (!wait && !r.fence.signalled()) return {false, std::nullopt};
        collect(r);
    }
    return {true, answers_.find(ticket)};
}

std::size_t FramePicks::in_flight() const {
    return static_cast<std::size_t>(
        std::count_if(readbacks_.begin(), readbacks_.end(), [](const Readback& r) { return r.fence.pending(); }));
}

}  // namespace splat_lod
