#pragma once
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
    unsigned long long frame_index() const { return frame_index_; }

private:
    MessageBus& bus_;
    AssetCache& assets_;
    std::unique_ptr<gl::ShaderLibrary> shaders_;  // created with the first frame (needs GL)
    std::vector<std::filesystem::path> shader_roots_;
    gl::GpuTimers timers_;
    std::vector<std::shared_ptr<RenderPass>> passes_;
    unsigned long long frame_index_ = 0;
};

}  // namespace engine
