#include "engine/render/renderer.h"

#include <algorithm>
#include <chrono>

#include <plugin_msgs/camera_state.h>
#include <plugin_msgs/frame_statistics.h>

#include "engine/core/error.h"
#include "engine/core/message_bus.h"
#include "engine/render/render_target.h"
#include "engine/scene/scene.h"

namespace engine {
namespace {

double elapsed_ms(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since).count();
}

plugin_msgs::CameraState camera_state(const CameraView& camera, unsigned long long frame) {
    const glm::mat4 to_world = glm::inverse(camera.view);
    const glm::vec3 forward = -glm::vec3(to_world[2]);
    const glm::vec3 up = glm::vec3(to_world[1]);
    plugin_msgs::CameraState s;
    s.frame_index = frame;
    s.position = {camera.position.x, camera.position.y, camera.position.z};
    s.forward = {forward.x, forward.y, forward.z};
    s.up = {up.x, up.y, up.z};
    s.fov_y_deg = glm::degrees(camera.fov_y);
    s.znear = camera.znear;
    s.zfar = camera.zfar;
    s.width = camera.width;
    s.height = camera.height;
    return s;
}

}  // namespace

Renderer::Renderer(MessageBus& bus, AssetCache& assets) : bus_(bus), assets_(assets) {}
Renderer::~Renderer() = default;

void Renderer::add_pass(std::shared_ptr<RenderPass> pass) {
    const std::string name = pass->name();
    if (std::any_of(passes_.begin(), passes_.end(), [&](const auto& p) { return p->name() == name; }))
        fail("render pass '" + name + "' is already registered");
    passes_.push_back(std::move(pass));
    std::stable_sort(passes_.begin(), passes_.end(),
                     [](const auto& a, const auto& b) { return a->order() < b->order(); });
}

void Renderer::remove_pass(const std::string& name) {
    std::erase_if(passes_, [&](const auto& p) { return p->name() == name; });
}

std::vector<std::string> Renderer::pass_names() const {
    std::vector<std::string> names;
    for (const auto& p : passes_) names.push_back(p->name());
    return names;
}

RenderPass* Renderer::find_pass(const std::string& name) const {
    for (const auto& p : passes_)
        if (p->name() == name) return p.get();
    return nullptr;
}

gl::ShaderLibrary& Renderer::shaders() {
    if (!shaders_) {
        shaders_ = std::make_unique<gl::ShaderLibrary>();
        for (const auto& root : shader_roots_) shaders_->add_root(root);
    }
    return *shaders_;
}

void Renderer::add_shader_root(const std::filesystem::path& root) {
    shader_roots_.push_back(root);
    if (shaders_) shaders_->add_root(root);
}

std::uint64_t Renderer::pick(glm::ivec2 pixel) {
    picks_.push_back({++tickets_, pixel});
    return tickets_;
}

PickResult Renderer::pick_result(std::uint64_t ticket, bool wait, RenderPass* only) const {
    if (ticket == 0 || ticket > tickets_) fail("Renderer::pick_result(): no pick has ticket " + std::to_string(ticket));
    if (ticket > drawn_tickets_) {
        if (wait) fail("Renderer::pick_result(): pick " + std::to_string(ticket) + " is not drawn yet: render a frame");
        return {false, std::nullopt};
    }
    PickResult result{true, std::nullopt};
    for (const auto& pass : passes_) {
        if (only != nullptr && pass.get() != only) continue;
        const PickResult answer = pass->pick_answer(ticket, wait);
        result.ready = result.ready && answer.ready;
        if (answer.hit && (!result.hit || answer.hit->depth < result.hit->depth)) result.hit = answer.hit;
    }
    if (!result.ready) result.hit.reset();
    return result;
}

void Renderer::render(const Scene& scene, const CameraView& camera, RenderTarget& target) {
    if (camera.width != target.width() || camera.height != target.height())
        fail("Renderer::render(): camera is " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
             " but the target is " + std::to_string(target.width()) + "x" + std::to_string(target.height()));
    const auto frame_start = std::chrono::steady_clock::now();
    bus_.publish(camera_state(camera, frame_index_));

    plugin_msgs::FrameStatistics stats;
    stats.frame_index = frame_index_;
    stats.width = target.width();
    stats.height = target.height();

    timers_.begin_frame();
    target.clear(scene.background.x, scene.background.y, scene.background.z);
    std::vector<PickRequest> picks;
    while (!picks_.empty() && picks.size() < kMaxPicksPerFrame) {
        picks.push_back(picks_.front());
        picks_.pop_front();
    }
    if (!picks.empty()) drawn_tickets_ = picks.back().ticket;
    FrameContext frame{scene, camera, target, shaders(), timers_, bus_, assets_, frame_index_, picks};
    for (const auto& pass : std::vector(passes_)) {  // a copy: passes may not change the list mid-frame
        const auto start = std::chrono::steady_clock::now();
        {
            gl::GpuTimerScope scope(timers_, pass->name());
            pass->execute(frame);
        }
        stats.passes.push_back({pass->name(), elapsed_ms(start), -1.0});
    }
    timers_.end_frame();

    // GPU times belong to an earlier frame: attach them by pass name with that frame's index.
    if (const auto& gpu = timers_.latest()) {
        stats.gpu_frame_index = timers_.latest_frame();
        for (auto& p : stats.passes)
            for (const auto& span : *gpu)
                if (span.name == p.name) p.gpu_ms = span.milliseconds;
    }
    stats.cpu_frame_ms = elapsed_ms(frame_start);
    bus_.publish(stats);
    ++frame_index_;
}

}  // namespace engine
