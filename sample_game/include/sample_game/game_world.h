#pragma once
// The game's world in a running engine: the manifest's props and terrain mesh as mesh nodes (drawn
// by the mesh pass, composited with the splats by depth; the splats of a prop's glTF, an import's far
// layer, as a splat component beside them), a sun and a sky light, and the chunks
// streamed by a ChunkStreamer through a SceneResidencySink under the node "chunks", where the splat
// pass's incremental GPU scene picks them up (the wiring of the plugin's tests/gpu/splat_streaming_test.cpp).
// Needs a current GL context for rendering (not to be built); the engine must have the splat_lod
// plugin started.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "engine/engine.h"
#include "engine/render/camera.h"
#include "sample_game/camera_path.h"
#include "sample_game/chunk_census.h"
#include "sample_game/game_settings.h"
#include "sample_game/world_ground.h"
#include "splat_lod/core/world_lock.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/splat_renderer.h"
#include "splat_lod/stream/chunk_streamer.h"
#include "splat_lod/stream/splat_budget.h"
#include "splat_lod/stream/stream_scene_sink.h"

namespace sample_game {

// Throws engine::Error when `folder` holds no world.json, saying how to make one (before a window
// or GL context is made, so that the message comes first).
void require_world_folder(const std::filesystem::path& folder);

class GameWorld {
public:
    // Reads `folder`/world.json, loads the props and the terrain mesh, starts the streamer, sets how
    // the GPU stores Gaussians and publishes the LOD settings. The GPU scene grows with what is
    // resident (by half again, a copy on the GPU) rather than holding the whole memory budget. Holds the folder's
    // shared lock until destroyed (splat_world refuses to rewrite it meanwhile). Throws engine::Error naming the file
    // on a missing or bad world, or when splat_world is writing into the folder.
    GameWorld(engine::Engine& engine, const std::filesystem::path& folder, const GameSettings& settings);
    ~GameWorld();  // stops the streamer before the scene it feeds goes
    GameWorld(const GameWorld&) = delete;
    GameWorld& operator=(const GameWorld&) = delete;

    const splat_lod::world::WorldManifest& manifest() const { return manifest_; }
    // The ground the walkthrough follows: the terrain of a generated world, the ground grid of an import.
    const WorldGround& ground() const { return ground_; }
    // The walkthrough's poses: settings().path_file's when one is named (path_file.h), else the world's
    // own path over its ground (world_path.h).
    std::vector<PathPose> path(int frames) const;
    const std::filesystem::path& folder() const { return folder_; }
    engine::Scene& scene() { return *scene_; }
    splat_lod::world::ChunkStreamer& streamer() { return *streamer_; }
    splat_lod::SplatRenderer& pass() { return *pass_; }
    const GameSettings& settings() const { return settings_; }

    // The game's camera at `eye` looking along `forward` (Y up), with near and far planes for its
    // height above the ground (game_settings.h).
    engine::CameraView camera(const glm::vec3& eye, const glm::vec3& forward, int width, int height) const;
    engine::CameraView camera(const PathPose& pose, int width, int height) const {
        return camera(pose.eye, pose.forward, width, height);
    }

    // One streamer update for this camera; returns its wall time in milliseconds. `velocity`: how far
    // the camera moved since the last update (world units), zero after a jump; the streamer's cut
    // coarsens early what the camera moves away from (chunk_streamer.h, "anticipation").
    double update_streaming(const engine::CameraView& camera, std::uint64_t frame, const glm::vec3& velocity = {});
    // New settings from the UI: LOD thresholds and budgets go to the streamer (the splat pass
    // already took the LodSettings message). The SH degree and sync mode are fixed at start.
    void set_settings(const GameSettings& settings);
    // Publishes settings().lod on the bus (the splat pass and the LOD panel take it from there).
    void publish_lod_settings();

    ChunkCensus census() const;
    // GPU bytes of every chunk fully resident (every level in whole pages), what the baseline holds.
    std::uint64_t whole_world_gpu_bytes() const;
    // GPU bytes of the props' splats (an import's far layer), resident all the time beside the streamed chunks.
    std::uint64_t props_gpu_bytes() const { return props_gpu_bytes_; }

    // Draws one frame with a few Gaussians of the first chunk so that every shader of the frame
    // is compiled before anything is timed, then removes them (nothing stays resident).
    void warm_up(int width, int height);

    // Replaces the streamer by one that keeps every level of every chunk resident, and loads them
    // all now (reads in this thread, no upload or memory limit): the baseline's "everything
    // resident" state. Returns the seconds it took. Throws engine::Error when a chunk fails.
    double load_whole_world(const std::function<void(std::size_t, std::size_t)>& progress);

private:
    void load_meshes();
    void start_streamer(const splat_lod::world::StreamerSettings& settings);

    engine::Engine& engine_;
    GameSettings settings_;
    std::filesystem::path folder_;
    // Held while the world streams, so that splat_world cannot regenerate it underneath (world_lock.h).
    splat_lod::world::WorldFolderLock lock_;
    splat_lod::world::WorldManifest manifest_;
    WorldGround ground_;
    std::unique_ptr<engine::Scene> scene_;
    engine::Node* chunks_root_ = nullptr;
    std::uint64_t props_gpu_bytes_ = 0;
    splat_lod::world::FileChunkSource source_;
    std::unique_ptr<splat_lod::world::SceneResidencySink> sink_;
    std::unique_ptr<splat_lod::world::ChunkStreamer> streamer_;
    // The splat budget (settings().lod.splat_budget) as the streamer's cut obeys it (splat_budget.h).
    splat_lod::world::SplatBudgetController budget_;
    std::optional<splat_lod::SplatRenderer> pass_;  // the plugin's splat pass, set once the engine runs
};

}  // namespace sample_game
