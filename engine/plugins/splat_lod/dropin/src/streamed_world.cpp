#include "streamed_world.h"

#include <algorithm>

#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/scene/node.h"

namespace splat_lod::dropin {
namespace fs = std::filesystem;
namespace sw = splat_lod::world;

namespace {

// The manifest, read only once the folder's stream lock is held (an import could be replacing it).
sw::WorldManifest read_manifest_under(const sw::WorldFolderLock& lock, const fs::path& folder) {
    lock.require();
    return sw::read_world_manifest(folder / sw::kManifestFileName);
}

// The map from the world's frame back to the capture's: p_capture = Rᵀ (p_world − t).
engine::Transform capture_from_world(const sw::WorldManifest& manifest, const fs::path& folder) {
    engine::Transform t;
    if (manifest.capture.empty()) return t;  // a generated world: its own frame
    glm::dmat3 r;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            r[col][row] = manifest.capture.rotation[static_cast<std::size_t>(row * 3 + col)];
    if (std::abs(glm::determinant(r) - 1.0) > 1e-3)
        engine::fail((folder / sw::kManifestFileName).string() + ": the capture's rotation is not a rotation");
    const glm::dmat3 back = glm::transpose(r);
    const auto& tr = manifest.capture.translation;
    t.rotation = glm::quat(glm::quat_cast(back));
    t.translation = glm::vec3(-(back * glm::dvec3(tr[0], tr[1], tr[2])));
    return t;
}

}  // namespace

void HoldingSink::upload(const sw::LevelPart& part) {
    shown_[part.chunk_id] = part.visible;
    sw::LevelPart held = part;
    held.visible = part.visible && !holding_;
    inner_.upload(held);
}

void HoldingSink::show(const std::string& chunk_id, bool visible) {
    shown_[chunk_id] = visible;
    inner_.show(chunk_id, visible && !holding_);
}

void HoldingSink::release_hold() {
    holding_ = false;
    for (const auto& [id, visible] : shown_) inner_.show(id, visible);
}

StreamedWorld::StreamedWorld(SplatComponent& component, const fs::path& folder, const DropInLodSettings& settings,
                             engine::AssetCache& assets)
    : folder_(folder),
      lock_(folder, sw::WorldFolderLock::Mode::stream),
      manifest_(read_manifest_under(lock_, folder)),
      settings_(settings.streaming) {
    if (component.node() == nullptr) engine::fail("splat_lod: " + folder.string() + ": the component has no node");
    settings_.gpu_sh_degree = std::min(settings_.gpu_sh_degree, component.sh_degree_cap);
    const engine::Transform placement = capture_from_world(manifest_, folder);
    root_ = &component.node()->add_child("streamed world");
    root_->transform() = placement;
    world::add_world_props(*root_, manifest_, folder_, assets, settings_.gpu_sh_degree);  // the far layer too
    engine::Node& chunks = root_->add_child("chunks");
    sink_ = std::make_unique<HoldingSink>(chunks, settings_.gpu_sh_degree);
}

StreamedWorld::~StreamedWorld() {
    streamer_.reset();  // its reader thread stops before the sink goes
}

bool StreamedWorld::cut_drawn() const {
    for (std::size_t i = 0; i < streamer_->chunk_count() + streamer_->group_count(); ++i) {
        const sw::ChunkStatus status = streamer_->chunk_status(i);
        if (status.in_cut && !status.drawn && !status.failed) return false;
    }
    return true;
}

void StreamedWorld::update(SplatComponent& component, const LodFrame& frame) {
    if (frame.focal_length_px <= 0.0f) return;  // no camera: nothing to stream for
    // With the bus the streamer takes the splat pass's thresholds from its LodSettings (chunk_streamer.h).
    if (!streamer_) {
        streamer_ = std::make_unique<sw::ChunkStreamer>(manifest_, folder_, settings_, source_, *sink_, frame.bus);
        // The splat budget that LodSettings sets reaches the cut through its controller (splat_budget.h).
        if (frame.bus) budget_ = std::make_unique<sw::SplatBudgetController>(*frame.bus);
    }
    // The camera in the world's frame; the velocity from the last frame's (none after a gap or a jump
    // of more than a chunk).
    const glm::vec3 eye = glm::vec3(glm::inverse(root_->world_matrix()) * glm::vec4(frame.camera_position, 1.0f));
    glm::vec3 velocity(0.0f);
    if (last_eye_ && frame.frame_index == last_frame_ + 1 && glm::distance(eye, *last_eye_) < manifest_.chunk_size_m)
        velocity = eye - *last_eye_;
    last_eye_ = eye;
    last_frame_ = frame.frame_index;
    streamer_->update({eye, frame.focal_length_px, frame.frame_index, velocity, budget_ ? budget_->update() : 1.0f});
    if (!sink_->holding() || !cut_drawn()) return;
    sink_->release_hold();
    component.cloud = nullptr;  // the trained scene's GPU memory goes with it
    engine::log_info("splat_lod: " + component.asset.filename().string() + ": streamed as a world from " +
                     folder_.string() + " from now on");
}

}  // namespace splat_lod::dropin
