#include "sample_game/game_world.h"

#include "sample_game/path_file.h"
#include "sample_game/world_path.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/assets/mesh_asset.h"
#include "engine/core/error.h"
#include "engine/render/fog_pass.h"
#include "engine/render/render_target.h"
#include "engine/scene/builtin_components.h"
#include "sample_game/world_path.h"
#include "splat_lod/splat_component.h"
#include "splat_lod/splat_lod_plugin.h"
#include "splat_lod/splat_renderer.h"
#include "splat_lod/stream/stream_policy.h"

namespace sample_game {
namespace sw = splat_lod::world;

namespace {

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void add_light(engine::Scene& scene, const std::string& name, engine::LightComponent::Kind kind,
               const glm::vec3& euler_deg, float intensity) {
    engine::Node& node = scene.root().add_child(name);
    node.transform().rotation = glm::quat(glm::radians(euler_deg));
    auto light = std::make_unique<engine::LightComponent>();
    light->kind = kind;
    light->intensity = intensity;
    node.attach(std::move(light));
}

// Gaussians in level `level` alone (1..4) of a chunk: its prefix minus the next coarser prefix.
std::uint64_t level_count(const sw::ChunkEntry& chunk, int level) {
    const std::uint64_t prefix = chunk.prefix_count[static_cast<std::size_t>(level - 1)];
    return level == sw::kLevels ? prefix : prefix - chunk.prefix_count[static_cast<std::size_t>(level)];
}

// The manifest, read only once the folder's lock is held (a run of splat_world could be replacing it).
sw::WorldManifest read_manifest_under(const sw::WorldFolderLock& lock, const std::filesystem::path& folder) {
    lock.require();
    return sw::read_world_manifest(folder / sw::kManifestFileName);
}

}  // namespace

void require_world_folder(const std::filesystem::path& folder) {
    const std::filesystem::path manifest = folder / sw::kManifestFileName;
    if (!std::filesystem::exists(manifest))
        engine::fail("sample_game: " + manifest.string() + ": not found; make the world with `splat_world --out " +
                     folder.string() + "` (scripts/demo does for the default world)");
}

GameWorld::GameWorld(engine::Engine& engine, const std::filesystem::path& folder, const GameSettings& settings)
    : engine_(engine),
      settings_(settings),
      folder_(folder),
      lock_(folder, sw::WorldFolderLock::Mode::stream),
      manifest_(read_manifest_under(lock_, folder)),
      ground_(WorldGround::of(manifest_)),
      scene_(std::make_unique<engine::Scene>()),
      budget_(engine.bus()) {
    validate(settings_);
    pass_.emplace(engine.renderer());
    scene_->background = {0.62f, 0.74f, 0.86f};  // a pale sky (display space)
    if (settings_.fog.enabled) {                 // the far field fades into the sky
        engine::FogSettings fog = settings_.fog;
        fog.colour = scene_->background;
        engine.renderer().add_pass(std::make_shared<engine::FogPass>(fog));
    }
    add_light(*scene_, "sun", engine::LightComponent::Kind::directional, {-50.0f, 30.0f, 0.0f}, 2.0f);
    add_light(*scene_, "sky", engine::LightComponent::Kind::ambient, {0.0f, 0.0f, 0.0f}, 0.5f);
    load_meshes();
    chunks_root_ = &scene_->root().add_child("chunks");
    // The sink caps what it hands the GPU at the settings' SH degree, so the GPU stride (and the
    // streamer's byte counts) are that degree's even for a world stored with more.
    sink_ = std::make_unique<sw::SceneResidencySink>(*chunks_root_, settings_.sh_degree);
    start_streamer(streamer_settings(settings_));
    pass_->settings().gpu_storage = settings_.gpu_storage;
    pass_->settings().frame_memory_limit = settings_.frame_memory_bytes;
    publish_lod_settings();
}

std::vector<PathPose> GameWorld::path(int frames) const {
    if (!settings_.path_file.empty()) return read_path_file(settings_.path_file, frames);
    return sample_world_path(ground_, frames);
}

GameWorld::~GameWorld() {
    streamer_.reset();
    if (settings_.fog.enabled) engine_.renderer().remove_pass("fog");
}

void GameWorld::load_meshes() {
    engine::Node& props = scene_->root().add_child("props");
    sw::add_world_props(props, manifest_, folder_, engine_.assets(), settings_.sh_degree);
    const sw::PageLayout pages = streamer_settings(settings_).gpu_pages;
    props.visit([&](const engine::Node& node) {
        if (const auto* splats = node.find_component<splat_lod::SplatComponent>(); splats && splats->cloud)
            props_gpu_bytes_ +=
                sw::gpu_bytes(splats->cloud->size(), std::min(splats->sh_degree_cap, splats->cloud->sh_degree), pages);
    });
}

void GameWorld::start_streamer(const sw::StreamerSettings& settings) {
    streamer_.reset();  // its reader thread stops before the replacement starts
    streamer_ = std::make_unique<sw::ChunkStreamer>(manifest_, folder_, settings, source_, *sink_, &engine_.bus());
}

engine::CameraView GameWorld::camera(const glm::vec3& eye, const glm::vec3& forward, int width, int height) const {
    const float above = eye.y - ground_.height(eye.x, eye.z);
    return engine::make_look_at_camera(eye, eye + forward, {0.0f, 1.0f, 0.0f}, glm::radians(settings_.fov_y_deg), width,
                                       height, near_plane_for(above), far_plane_for(manifest_.size_m));
}

double GameWorld::update_streaming(const engine::CameraView& camera, std::uint64_t frame, const glm::vec3& velocity) {
    const auto start = Clock::now();
    streamer_->update({camera.position, camera.focal_length(), frame, velocity, budget_.update()});
    return milliseconds_since(start);
}

void GameWorld::set_settings(const GameSettings& settings) {
    GameSettings next = settings;
    next.sh_degree = settings_.sh_degree;
    next.sync_streaming = settings_.sync_streaming;
    validate(next);
    settings_ = next;
    streamer_->set_settings(streamer_settings(settings_));
}

void GameWorld::publish_lod_settings() {
    engine_.bus().publish(settings_.lod);
}

ChunkCensus GameWorld::census() const {
    ChunkCensus census;
    for (std::size_t i = 0; i < streamer_->chunk_count(); ++i) {
        const sw::ChunkStatus status = streamer_->chunk_status(i);
        // The least advanced of the levels the view needs (LevelState is ordered absent → resident).
        auto state = sw::LevelState::resident;
        for (int level = std::clamp(status.finest_needed_level, 1, sw::kLevels); level <= sw::kLevels; ++level)
            state = std::min(state, status.levels[static_cast<std::size_t>(level - 1)]);
        switch (state) {
            case sw::LevelState::absent:
                ++census.absent;
                break;
            case sw::LevelState::requested:
                ++census.requested;
                break;
            case sw::LevelState::loaded:
                ++census.loaded;
                break;
            case sw::LevelState::partial:
                ++census.partial;
                break;
            case sw::LevelState::resident:
                ++census.resident;
                break;
        }
        ++census.finest_resident[static_cast<std::size_t>(std::clamp(status.finest_resident_level, 0, sw::kLevels))];
        census.failed += status.failed ? 1u : 0u;
    }
    return census;
}

std::uint64_t GameWorld::whole_world_gpu_bytes() const {
    const sw::StreamerSettings& s = streamer_->settings();
    std::uint64_t total = 0;
    for (const auto& chunk : manifest_.chunks)
        for (int level = 1; level <= sw::kLevels; ++level)
            total += sw::gpu_bytes(level_count(chunk, level), s.gpu_sh_degree, s.gpu_pages);
    return total;
}

void GameWorld::warm_up(int width, int height) {
    const auto chunk = std::find_if(manifest_.chunks.begin(), manifest_.chunks.end(),
                                    [](const sw::ChunkEntry& c) { return c.prefix_count[sw::kLevels - 1] > 0; });
    if (chunk == manifest_.chunks.end()) return;  // no Gaussians anywhere: nothing to compile for
    auto component = std::make_unique<splat_lod::SplatComponent>();
    component->cloud = std::make_shared<const splat_lod::SplatCloud>(
        source_.read(folder_ / chunk->file, *chunk, 0, chunk->prefix_count[sw::kLevels - 1]));
    component->sh_degree_cap = settings_.sh_degree;
    engine::Node& node = scene_->root().add_child("warm-up");
    node.attach(std::move(component));
    const glm::vec3 centre = 0.5f * (chunk->bounds_min + chunk->bounds_max);
    const engine::CameraView view = camera(centre + glm::vec3(0.0f, manifest_.chunk_size_m, manifest_.chunk_size_m),
                                           glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f)), width, height);
    engine::RenderTarget target(width, height);
    splat_lod::render_complete(engine_, *scene_, view, target);
    scene_->root().remove_child(node);
    engine_.renderer().render(*scene_, view, target);  // frees the warm-up's pages
    engine_.renderer().timers().wait_all();
    pass_->wait_for_statistics(engine_.bus());
}

double GameWorld::load_whole_world(const std::function<void(std::size_t, std::size_t)>& progress) {
    const auto start = Clock::now();
    streamer_->release_all();
    const std::uint64_t total = whole_world_gpu_bytes();
    sw::StreamerSettings s = streamer_settings(settings_);
    s.memory_budget_bytes = total + 1;
    s.upload_budget_bytes_per_frame = std::max<std::uint64_t>(total, s.upload_budget_bytes_per_frame);
    s.load_distance_scale = 1e9f;  // every level is wanted from anywhere
    s.group_cell_px = 0.0f;        // every chunk drawn from its own levels, no group
    s.fade_frames = 0;             // drawn whole once resident: a fade would thin the first frames drawn
    s.background_thread = false;
    s.max_requests_in_flight = 64;
    start_streamer(s);
    pass_->reserve(
        total / sw::gpu_bytes(s.gpu_pages.page_gaussians, s.gpu_sh_degree, s.gpu_pages) * s.gpu_pages.page_gaussians,
        s.gpu_sh_degree);
    const glm::vec3 above = ground_.centre() + glm::vec3(0.0f, manifest_.size_m, 0.0f);
    std::size_t complete = 0, stalled = 0;
    for (std::uint64_t frame = 0; complete < streamer_->chunk_count(); ++frame) {
        streamer_->update({above, 1000.0f, frame});
        std::size_t now_complete = 0;
        for (std::size_t i = 0; i < streamer_->chunk_count(); ++i) {
            const sw::ChunkStatus status = streamer_->chunk_status(i);
            if (status.failed)
                engine::fail("sample_game: baseline: " + (folder_ / manifest_.chunks[i].file).string() +
                             " could not be loaded: " + status.failure);
            now_complete += status.finest_resident_level == 1 ? 1 : 0;
        }
        stalled = now_complete > complete ? 0 : stalled + 1;
        complete = now_complete;
        if (progress) progress(complete, streamer_->chunk_count());
        if (stalled > 1000)
            engine::fail("sample_game: baseline: loading every chunk made no progress for 1000 updates (" +
                         std::to_string(complete) + " of " + std::to_string(streamer_->chunk_count()) + " complete)");
    }
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace sample_game
