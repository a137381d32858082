#pragma once
#include <cstdint>
#include <span>
#include <string>

#include "engine/render/camera.h"
#include "engine/render/picking.h"

namespace engine {

class Scene;
class RenderTarget;
class MessageBus;
class AssetCache;
namespace gl {
class ShaderLibrary;
class GpuTimers;
}  // namespace gl

// Everything a pass may use while drawing one frame.
struct FrameContext {
    const Scene& scene;
    const CameraView& camera;
    RenderTarget& target;
    gl::ShaderLibrary& shaders;
    gl::GpuTimers& timers;
    MessageBus& bus;
    AssetCache& assets;
    unsigned long long frame_index = 0;
    // The pixels this frame is asked about (Renderer::pick); a pass that draws surfaces answers them
    // through pick_answer().
    std::span<const PickRequest> picks;
};

// One step of a frame. Passes run in ascending order(); the renderer times each one (CPU and
// GPU) under its name.
class RenderPass {
public:
    virtual ~RenderPass() = default;
    virtual std::string name() const = 0;
    virtual int order() const = 0;
    virtual void execute(FrameContext& frame) = 0;
    // What this pass drew under the pixel of `ticket` (picking.h): not ready while its answer is on
    // the GPU (`wait`: read it back now, blocking). A pass that draws no surfaces answers nothing.
    virtual PickResult pick_answer(std::uint64_t ticket, bool wait) {
        (void)ticket;
        (void)wait;
        return {true, std::nullopt};
    }
};

// Conventional orders: meshes write depth first, plugin passes read it, late meshes are drawn
// against what both left, then post and UI.
namespace pass_order {
inline constexpr int mesh = 100;
inline constexpr int plugin = 200;
inline constexpr int late_mesh = 250;
inline constexpr int post = 300;
inline constexpr int ui = 400;
}  // namespace pass_order

}  // namespace engine
