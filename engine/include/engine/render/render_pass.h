#pragma once
#include <string>

#include "engine/render/camera.h"

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
};

// One step of a frame. Passes run in ascending order(); the renderer times each one (CPU and
// GPU) under its name.
class RenderPass {
public:
    virtual ~RenderPass() = default;
    virtual std::string name() const = 0;
    virtual int order() const = 0;
    virtual void execute(FrameContext& frame) = 0;
};

// Conventional orders: meshes write depth first, plugin passes read it, then post and UI.
namespace pass_order {
inline constexpr int mesh = 100;
inline constexpr int plugin = 200;
inline constexpr int post = 300;
inline constexpr int ui = 400;
}  // namespace pass_order

}  // namespace engine
