#pragma once
// An imported world streamed under a splat component's node (drop_in_lod.h): a child node "streamed
// world" that undoes the import's capture → world map, the chunks under it through a sink that keeps
// them hidden while the trained scene is still drawn, the far layer and props, and the chunk streamer.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "splat_lod/core/world_lock.h"
#include "splat_lod/dropin/drop_in_lod.h"
#include "splat_lod/stream/splat_budget.h"
#include "splat_lod/stream/stream_scene_sink.h"

namespace engine {
class AssetCache;
class Node;
}  // namespace engine

namespace splat_lod::dropin {

// The scene's sink, except that every part stays hidden while holding() (the trained scene is drawn
// over the same ground); release_hold() shows what the streamer shows.
class HoldingSink final : public world::ResidencySink {
public:
    HoldingSink(engine::Node& root, int sh_degree_cap) : inner_(root, sh_degree_cap) {}
    void upload(const world::LevelPart& part) override;
    void release(const std::string& chunk_id, int level) override { inner_.release(chunk_id, level); }
    void show(const std::string& chunk_id, bool visible) override;
    void fade(const std::string& chunk_id, int level, float opacity) override { inner_.fade(chunk_id, level, opacity); }
    bool holding() const { return holding_; }
    void release_hold();

private:
    world::SceneResidencySink inner_;
    std::map<std::string, bool> shown_;  // what the streamer last asked for, per chunk or group
    bool holding_ = true;
};

class StreamedWorld {
public:
    // Reads `folder`'s world (holding its stream lock) and builds the nodes under `component`'s node.
    // Throws engine::Error naming the folder or file on a bad world.
    StreamedWorld(SplatComponent& component, const std::filesystem::path& folder, const DropInLodSettings& settings,
                  engine::AssetCache& assets);
    ~StreamedWorld();  // stops the streamer; the nodes go with the scene
    StreamedWorld(const StreamedWorld&) = delete;
    StreamedWorld& operator=(const StreamedWorld&) = delete;

    // One streamer update for the frame's camera (turned into the world's frame). Releases the trained
    // cloud once the cut is drawn everywhere.
    void update(SplatComponent& component, const LodFrame& frame);
    bool holding() const { return sink_->holding(); }
    world::ChunkStreamer& streamer() { return *streamer_; }
    const std::filesystem::path& folder() const { return folder_; }

private:
    bool cut_drawn() const;

    std::filesystem::path folder_;
    world::WorldFolderLock lock_;
    world::WorldManifest manifest_;
    world::StreamerSettings settings_;
    engine::Node* root_ = nullptr;  // "streamed world", a child of the component's node
    std::unique_ptr<HoldingSink> sink_;
    world::FileChunkSource source_;
    std::unique_ptr<world::ChunkStreamer> streamer_;
    std::unique_ptr<world::SplatBudgetController> budget_;  // with a bus
    std::optional<glm::vec3> last_eye_;                     // the last update's camera in the world's frame
    std::uint64_t last_frame_ = 0;
};

}  // namespace splat_lod::dropin
