#include "lod_update_pass.h"

#include "engine/core/message_bus.h"
#include "engine/scene/scene.h"
#include "plugin_msgs/background_work.h"

namespace splat_lod {

bool SplatComponent::update_lod(const LodFrame& frame) {
    if (!lod_job) return false;
    const auto before = cloud;
    // The job may end its own life through the component (a failure); keep it alive for the call.
    const std::shared_ptr<LodJob> job = lod_job;
    if (!job->update(*this, frame) && lod_job == job) lod_job.reset();
    return cloud != before;
}

void LodSwapPass::execute(engine::FrameContext& frame) {
    LodFrame view;
    view.camera_position = frame.camera.position;
    view.focal_length_px = frame.camera.focal_length();
    view.frame_index = frame.frame_index;
    view.bus = &frame.bus;
    std::vector<std::string> lines;
    for (SplatComponent* component : frame.scene.components<SplatComponent>()) {
        if (!component->lod_job) continue;
        component->update_lod(view);
        if (component->lod_job)
            if (std::string line = component->lod_job->status(); !line.empty()) lines.push_back(std::move(line));
    }
    if (lines == published_) return;
    published_ = lines;
    frame.bus.publish(plugin_msgs::BackgroundWork{source_, frame.frame_index, std::move(lines)});
}

}  // namespace splat_lod
