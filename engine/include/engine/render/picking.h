#pragma once
// Picking: what a frame drew under a pixel. Renderer::pick(pixel) asks the next frame drawn; every pass
// that draws surfaces answers for its own (RenderPass::pick_answer): the mesh passes at once, by a ray
// cast on the CPU against their triangles, a plugin pass when its GPU work is read back (a frame or more
// later, without a stall). The nearest answer wins: the one with the smallest view depth.
#include <cstdint>
#include <map>
#include <optional>

#include <glm/glm.hpp>

namespace engine {

class Node;
class Scene;
struct Component;
struct CameraView;

// At most this many picks are answered by one frame; later ones wait for the next frame.
inline constexpr std::size_t kMaxPicksPerFrame = 64;

struct PickHit {
    glm::dvec3 position{0.0};  // world
    double depth = 0.0;        // view depth z = −z_view of the point
    // The component hit and its node: valid while the scene that was drawn holds them (compare them
    // with the scene's, do not keep them across scene changes).
    const Node* node = nullptr;
    const Component* component = nullptr;
};

struct PickResult {
    bool ready = false;          // false while an answer is still on its way from the GPU
    std::optional<PickHit> hit;  // empty: nothing under the pixel (or not ready)
};

struct PickRequest {
    std::uint64_t ticket = 0;
    glm::ivec2 pixel{0};  // image space: top-left origin, the pixel's centre is picked
};

// The world point at view depth `depth` on the ray through the centre of `pixel`.
glm::dvec3 pixel_ray_point(const CameraView& camera, glm::ivec2 pixel, double depth);

// The nearest triangle of the scene's mesh components (`late` selects MeshComponent::late ones or the
// others) hit by the ray through the centre of `pixel` in front of the near plane; nothing when none is.
std::optional<PickHit> pick_meshes(const Scene& scene, const CameraView& camera, glm::ivec2 pixel, bool late);

// A pass's answers by ticket, the newest `kKept` of them.
class PickAnswers {
public:
    static constexpr std::size_t kKept = 4096;
    void add(std::uint64_t ticket, const std::optional<PickHit>& hit);
    // The answer for `ticket`; nothing (no hit) for a ticket never answered here. Throws engine::Error
    // for a ticket whose answer was dropped to keep the newest kKept.
    std::optional<PickHit> find(std::uint64_t ticket) const;

private:
    std::map<std::uint64_t, std::optional<PickHit>> answers_;
    std::uint64_t dropped_below_ = 0;  // answers of tickets below this one were dropped
};

}  // namespace engine
