#pragma once
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "engine/gl/gpu_timers.h"
#include "engine/gl/shader_library.h"
#include "engine/render/render_pass.h"

namespace engine {

class MessageBus;
class AssetCache;

// Runs the ordered passes of a frame into a RenderTarget and publishes
// plugin_msgs::FrameStatistics (CPU time per pass now, GPU time per pass as it becomes
// available a few frames later) on the message bus.
class Renderer {
public:
    Renderer(MessageBus& bus, AssetCache& assets);
    ~Renderer();

    // Takes part in every frame from now on; names must be unique.
    void add_pass(std::shared_ptr<RenderPass> pass);
    void remove_pass(const std::string& name);
    std::vector<std::string> pass_names() const;
    RenderPass* find_pass(const std::string& name) const;

    // Draws the scene from `camera` into `target`; needs a current GL context.
    void render(const Scene& scene, const CameraView& camera, RenderTarget& target);

    gl::ShaderLibrary& shaders();
    // A folder of shader files that passes may name, searched after the engine's own (a plugin adds
    // its shaders folder at startup, before or after the first frame).
    void add_shader_root(const std::filesystem::path& root);
    gl::GpuTimers& timers() { return timers_; }

    // Picking (picking.h): asks what the next frame draws under `pixel` (image space, top-left origin);
    // returns the ticket of the answer. A frame answers at most kMaxPicksPerFrame, the oldest first.
    std::uint64_t pick(glm::ivec2 pixel);
    // The nearest of the passes' answers: not ready before a frame has drawn the ticket's pixel or while
    // a pass's answer is on its way (`wait`: reads them back now, blocking; throws engine::Error
    // when no frame has drawn it yet). Never blocks without `wait`. With `only`, that pass's answer alone.
    PickResult pick_result(std::uint64_t ticket, bool wait = false, RenderPass* only = nullptr) const;
    unsigned long long frame_index() const { return frame_index_; }

private:
    MessageBus& bus_;
    AssetCache& assets_;
    std::unique_ptr<gl::ShaderLibrary> shaders_;  // created with the first frame (needs GL)
    std::vector<std::filesystem::path> shader_roots_;
    gl::GpuTimers timers_;
    std::vector<std::shared_ptr<RenderPass>> passes_;
    unsigned long long frame_index_ = 0;
    std::deque<PickRequest> picks_;    // asked, not drawn yet
    std::uint64_t tickets_ = 0;        // the last ticket handed out
    std::uint64_t drawn_tickets_ = 0;  // tickets up to this one were drawn
};

}  // namespace engine
